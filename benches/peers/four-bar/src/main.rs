//! The `four-bar` crate's path synthesis (differential evolution on its distance-discrepancy
//! path signature, `syn::FbDDSyn`) on the literature's untimed cases (b) six points on a line and
//! (c) ten points on an ellipse; the timed cases (a) and (d) it cannot express (its synthesis
//! fits the shape of a curve, with no crank angle at a target and no precision points).
//!
//! Each run's design is scored in the literature's measure with code written here: the sum over
//! the targets of the squared distance to the nearest of 36 000 points of its coupler curve
//! (order not enforced: a lower bound of the ordered error kinloop reports), and checked against
//! the case's bounds. Prints one line per run and a summary; one thread.

use four_bar::{FourBar, mh, syn};
use std::time::Instant;

struct Case {
    name: &'static str,
    targets: Vec<[f64; 2]>,
    mode: syn::Mode,
    links: (f64, f64),
    coords: (f64, f64),
    threshold: f64,
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "b: 6 points on a line",
            targets: (0..6).map(|k| [20.0, 20.0 + 5.0 * k as f64]).collect(),
            mode: syn::Mode::Open,
            links: (5.0, 60.0),
            coords: (-60.0, 60.0),
            threshold: 1e-2,
        },
        Case {
            name: "c: 10 points on an ellipse",
            targets: vec![
                [20.0, 10.0],
                [17.66, 15.142],
                [11.736, 17.878],
                [5.0, 16.928],
                [0.60307, 12.736],
                [0.60307, 7.2638],
                [5.0, 3.0718],
                [11.736, 2.1215],
                [17.66, 4.8577],
                [20.0, 10.0],
            ],
            mode: syn::Mode::Closed,
            links: (5.0, 80.0),
            coords: (-80.0, 80.0),
            threshold: 1e-2,
        },
    ]
}

/// Sum over the targets of the squared distance to the nearest curve point.
fn nearest_sse(curve: &[[f64; 2]], targets: &[[f64; 2]]) -> f64 {
    targets
        .iter()
        .map(|t| curve.iter().map(|p| (p[0] - t[0]).powi(2) + (p[1] - t[1]).powi(2)).fold(f64::INFINITY, f64::min))
        .sum()
}

/// The design in the literature's variables, and whether it lies within the case's bounds.
fn within_bounds(fb: &FourBar, case: &Case) -> bool {
    let (n, u) = (&fb.norm, &fb.unnorm);
    let links = [n.l1, u.l2, n.l3, n.l4];
    let coords = [n.l5 * n.g.cos(), n.l5 * n.g.sin(), u.p1x, u.p1y];
    links.iter().all(|&l| l >= case.links.0 && l <= case.links.1)
        && coords.iter().all(|&c| c >= case.coords.0 && c <= case.coords.1)
}

fn main() {
    let runs: u64 = std::env::args().nth(1).map_or(20, |s| s.parse().expect("runs"));
    let (gens, pop) = (200, 100);
    println!("four-bar 7.0.5, De::default(), {pop} individuals, {gens} generations, {runs} seeds per case");
    for case in cases() {
        let clock = Instant::now();
        let mut errors = Vec::new();
        let mut inside = 0;
        for seed in 0..runs {
            let func = syn::FbDDSyn::from_curve(case.targets.clone(), case.mode);
            let s = mh::Solver::build(mh::De::default(), func)
                .seed(seed)
                .task(|ctx| ctx.r#gen == gens)
                .pop_num(pop)
                .solve();
            let fb: FourBar = s.into_result();
            let curve = fb.curve(36_000);
            let e = if curve.len() < 2 { f64::INFINITY } else { nearest_sse(&curve, &case.targets) };
            let ok = within_bounds(&fb, &case);
            inside += usize::from(ok);
            println!("  seed {seed}: sum of squares {e:.6e}, within bounds {ok}, {fb:?}");
            errors.push(e);
        }
        let time = clock.elapsed().as_secs_f64();
        let best = errors.iter().copied().fold(f64::INFINITY, f64::min);
        let reached = errors.iter().filter(|&&e| e <= case.threshold).count();
        println!(
            "{} | runs {runs} | best {best:.6e} | reaching <= {:e}: {reached}/{runs} | within bounds {inside}/{runs} | {time:.2} s",
            case.name, case.threshold
        );
    }
}
