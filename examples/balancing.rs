//! External balancing of the asymmetric rhombic drive (`docs/papers.md`, paper 004): the centre of mass
//! of the reciprocating masses over a crank turn, its Fourier harmonics, the residual unbalance
//! after counterweights cancel the first harmonic, and the dimensionless design that minimises
//! it for a given mass ratio.
//!
//! **Model.** The kinematics are those of the drive of paper 000, Fig. 1 (`kinloop` solves them;
//! nothing is expanded in series), made dimensionless by the working crank radius `r = R_P = 1`:
//! crank centre A = (0, k); working piston C at (X_C, 0) with rod `gamma = L_P/r`; displacer F
//! at (X_F, k - k_b rho) with crank arm `rho = R_B/r` at angle `delta` from the working arm and
//! rod `gamma_b = L_B/r`; `k = e_P/R_P` and `k_b = e_B/R_B` are the relative eccentricities of
//! the two piston lines from the crank centre (paper 000's `k_P`, `k_B`). The reciprocating
//! masses are the piston group `M_s` (piston and the piston end of its rod) and the displacer
//! group `M_s1`, `M' = M_s/M_s1`; with `x = -X_C` and `x1 = X_F` their distances from the crank
//! centre on either side (`x = r cos a + l cos b` of the paper),
//!
//! ```text
//! X_c(alpha) = (M_s x - M_s1 x1) / (M_s + M_s1) = -(M' X_C + X_F) / (M' + 1)
//! X_c1 = a0 + a1 cos(alpha) + b1 sin(alpha)      (balanced by counterweights)
//! D = max over a turn of |X_c - X_c1|            (residual unbalance, in crank radii)
//! ```
//!
//! **Design problem.** The paper names the paper's parameters (rod-length ratio `gamma`,
//! relative eccentricity, a parameter `k`, mass ratio `M'`) without defining all of them; this
//! example reads its "typical case k = 0.3, gamma = 2" as the working group `gamma = 2`,
//! `k = 0.3`, held fixed, and takes as reference design the symmetric rhombic arrangement: both
//! rods on one crank pin (`delta = 0`), `rho = 1`, `gamma_b = 2`, `k_b = 0.3`. The free design
//! parameters are the displacer group's `rho` in [0.5, 2], `gamma_b` in [1.5, 6], `k_b` in
//! [-1, 1] and `delta` in [-180°, 180°]; `D` is minimised by Nelder–Mead in that box for
//! `M' = 1.5` (a design that does not assemble over the whole turn counts as infinitely bad). The optimum is
//! known in closed form: exact balance (`D = 0`) when the displacer group is the working group
//! scaled by `M'` (`rho = M'`, `gamma_b = M' gamma`, `k_b = k`, `delta = 0`), since then
//! `M' X_C + X_F = 2 M' cos(alpha)`. In that design piston and displacer move in antiphase, of
//! no use to a Stirling engine; so the example minimises `D` a second time with the phase shift
//! between the outer dead centres (piston farthest left, displacer farthest right) held at
//! `PHASE = 90°`, which fixes `delta` in closed form from the other parameters: the second
//! harmonics of piston and displacer then add up instead of cancelling, and the optimum lies on
//! the bounds of the ranges.
//!
//! Run with `cargo run --release -p kinloop-examples --example balancing`.

use kinloop::analysis::NelderMead;
use kinloop::plot::{self, Axis, Kind, Panel, Series};
use kinloop_fixtures::balancing::{Balance, PHASE, SAMPLES, design, phased, unbalance};
use std::f64::consts::{PI, TAU};

/// X_c and its residual X_c - X_c1 against the crank angle (radians).
struct Curves {
    x_c: Vec<(f64, f64)>,
    residual: Vec<(f64, f64)>,
}

/// A design's centre of mass over a turn, as the example prints it.
pub struct Analysed {
    /// The amplitudes of the harmonics 1 to 6 of X_c.
    pub amplitudes: [f64; 6],
    /// The residual unbalance D after the first harmonic.
    pub d: f64,
    /// The crank angle (radians) where the residual is largest.
    pub at: f64,
    curves: Curves,
}

/// A design's harmonics and D, and its curves over the turn.
pub fn analyse(m: &Balance) -> Result<Analysed, Box<dyn std::error::Error>> {
    let turn = m.sampled(0.0, TAU, SAMPLES + 1, &m.guess(0.0))?;
    let f = turn.fourier(Balance::COL.xc, 6)?;
    let r = turn.unbalance(Balance::COL.xc, 1)?;
    let jets = turn.jets(Balance::COL.xc)?;
    Ok(Analysed {
        amplitudes: std::array::from_fn(|k| f.amplitude(k + 1)),
        d: r.max_abs,
        at: r.at.x,
        curves: Curves {
            x_c: jets.iter().map(|j| (j.x, j.value)).collect(),
            residual: jets.iter().map(|j| (j.x, j.value - r.fourier.eval_upto(1, j.x).0)).collect(),
        },
    })
}

/// Prints a design's harmonics and D; returns its curves over the turn.
fn describe(name: &str, m: &Balance) -> Result<Curves, Box<dyn std::error::Error>> {
    let a = analyse(m)?;
    println!(
        "{name}: rho = {:.6}, gamma_b = {:.6}, k_b = {:.6}, delta = {:.6}°",
        m.rho,
        m.gamma_b,
        m.k_b,
        m.delta.to_degrees()
    );
    let amps: Vec<String> = a.amplitudes.iter().map(|v| format!("{v:.3e}")).collect();
    println!("  harmonic amplitudes of X_c (1..6): {}", amps.join(", "));
    println!("  residual unbalance D = {:.6e} at alpha = {:.3}°", a.d, a.at.to_degrees());
    Ok(a.curves)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let reference = design([1.0, 2.0, 0.3, 0.0]);
    let mass_ratio = reference.mass_ratio;
    println!(
        "Balancing of the rhombic drive (paper 004): gamma = {}, k = {}, M' = {mass_ratio}\n",
        reference.gamma, reference.k
    );
    let before = describe("reference design", &reference)?;
    // The paper's trends, on the reference family (symmetric groups, one crank pin).
    let family = |gamma: f64, k: f64| {
        let m = Balance { gamma, k, gamma_b: gamma, k_b: k, ..reference };
        unbalance(&m, SAMPLES)
    };
    let row =
        |xs: &[f64], f: &dyn Fn(f64) -> f64| xs.iter().map(|&x| format!("{:.4e}", f(x))).collect::<Vec<_>>().join("  ");
    println!(
        "  D against the rod-length ratio gamma = 1.5, 2, 3, 4 (k = 0.3): {}",
        row(&[1.5, 2.0, 3.0, 4.0], &|g| family(g, 0.3))
    );
    println!(
        "  D against the eccentricity k = 0, 0.3, 0.6, 0.9 (gamma = 2):    {}",
        row(&[0.0, 0.3, 0.6, 0.9], &|k| family(2.0, k))
    );

    let (lo, hi) = ([0.5, 1.5, -1.0, -PI], [2.0, 6.0, 1.0, PI]);
    let cfg = NelderMead::default().with_max_evaluations(10_000).with_tolerances(1e-12, 1e-8);
    let best = cfg.minimize_boxed(|p| unbalance(&design(*p), SAMPLES), [1.0, 2.0, 0.3, 0.0], lo, hi)?;
    println!(
        "\nminimum of D over rho, gamma_b, k_b, delta (Nelder-Mead: {} evaluations, converged = {}):",
        best.evaluations,
        best.converged()
    );
    let optimum = design(best.x);
    let balanced = describe("optimum", &optimum)?;
    println!(
        "  closed-form optimum (exact balance): rho = {mass_ratio}, gamma_b = {}, k_b = {}, delta = 0, D = 0",
        mass_ratio * reference.gamma,
        reference.k
    );

    let (lo, hi) = ([lo[0], lo[1], lo[2]], [hi[0], hi[1], hi[2]]);
    let best90 = cfg.minimize_boxed(|p| unbalance(&phased(*p), SAMPLES), [1.0, 2.0, 0.3], lo, hi)?;
    println!(
        "\nwith the phase shift held at {}° (Nelder-Mead: {} evaluations, converged = {}):",
        PHASE.to_degrees(),
        best90.evaluations,
        best90.converged()
    );
    let phased_optimum = phased(best90.x);
    let after = describe("optimum with the phase shift", &phased_optimum)?;

    let dir = plot::figure_dir("balancing")?;
    let designs = [
        ("reference design", &before),
        ("optimum (exact balance)", &balanced),
        ("optimum with 90° phase shift", &after),
    ];
    // Lengths in units of the working crank radius r = 1.
    let length = Kind::length("units of r");
    let panel = |name: &str, curve: fn(&Curves) -> &Vec<(f64, f64)>| {
        designs.iter().fold(Panel::new(Axis::new(name, length.clone())), |p, &(label, c)| {
            p.with(Series::new(label, length.clone(), curve(c).clone()))
        })
    };
    plot::panels(
        &dir.join("centre_of_mass.svg"),
        "Rhombic drive balancing (M' = 1.5): centre of mass of the reciprocating masses",
        &Axis::angle("crank angle α"),
        &[panel("centre of mass X_c", |c| &c.x_c), panel("residual X_c − X_c1", |c| &c.residual)],
    )?;
    println!("\nwrote centre_of_mass.svg to {}", dir.display());
    Ok(())
}
