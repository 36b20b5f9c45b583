//! The assembly mode of a mechanism beyond the closed forms' sizes is the one size 1 gives from
//! the same guess. At size 1 a closed form picks its root by the guess's side (the sign of its
//! block's Jacobian determinant at the guess, see `codegen/src/emit/closed_form.rs`); beyond
//! `1e±144` the rescue solves the position by Newton over the whole system
//! (`runtime/src/mechanism/extreme_scale.rs`), which went wherever it converged: a four-bar
//! driven by its rocker, from its declared guess, gave the other assembly mode than size 1 at
//! inputs such as `-0.7`, `0.8` and `1.0` at `1e200` (at `0.8`, size 1 `(-0.598, 0.183)`, the
//! rescue `(-1.092, 4.410)`), a silent wrong answer.

use kinloop::{Mechanism, NewtonConfig};

// The rocker-driven four-bar, its lengths at size 1 (rocker 3, coupler 3.5, crank 1, frame 4:
// the rocker swings where `2.5 <= |BD| <= 4.5`, `B` its end, `cos phi` in `[19 / 96, 25 / 32]`,
// on either side of the frame) and the sizes beyond the closed forms', as the limit positions'
// tests have them.
use crate::limit_positions_extreme_scales::{ROCKER, RockerDriven, SIZES};

fn at(k: f64) -> RockerDriven {
    let [a, b, c, d] = ROCKER.map(|l| l * k);
    RockerDriven { a, b, c, d }
}

/// 24 inputs over both of the rocker's ranges, `0.02` rad inside their limits: there the two
/// assembly modes are more than `0.2` rad apart (the coupler turns by about
/// `sqrt(slope * 0.02 / kappa)` from the fold), so a solve in the other mode is far outside
/// the tolerance below.
fn inputs() -> Vec<f64> {
    let (lo, hi) = ((25.0f64 / 32.0).acos() + 0.02, (19.0f64 / 96.0).acos() - 0.02);
    let n = 12;
    let range: Vec<f64> = (0..n).map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64).collect();
    range.iter().map(|x| -x).chain(range.iter().copied()).collect()
}

/// Two guesses: the declared one, and its mirror across the frame (`beta`, `gamma` negated,
/// the crank's end below where the declared guess has it above), the other assembly mode at
/// every input here (checked at size 1).
fn guesses() -> [[f64; 2]; 2] {
    let declared = at(1.0).guess_flat(&[0.0]);
    [declared, declared.map(|q| -q)]
}

/// How far the angles at size `k` may be from size 1's: the lengths `ROCKER * k` are rounded
/// to half an ulp (`k` is not a power of two), the closed form and Newton each leave their
/// angles within a few ulps, and 0.02 rad inside a limit the angles move by at most about
/// `1 / sqrt(0.02)` (the fold's square root) times a relative change of the lengths: a few
/// `1e-15`. The other assembly mode is more than `0.2` rad away.
const TOL: f64 = 1e-12;

#[test]
fn the_rescue_keeps_size_ones_assembly_mode() {
    let cfg = NewtonConfig::default();
    let one = at(1.0);
    let mut wrong = Vec::new();
    for x in inputs() {
        let bases = guesses().map(|g| {
            let (q, _) = one.position_flat(&[x], &g, &cfg).unwrap_or_else(|e| panic!("phi {x} at size 1: {e}"));
            q
        });
        // The two guesses are the two modes at size 1, so both are compared.
        assert!((bases[0][0] - bases[1][0]).abs() > 0.1, "phi {x}: both guesses give one mode at size 1: {bases:?}");
        for (guess, base) in guesses().iter().zip(bases) {
            for k in SIZES {
                let m = at(k);
                let (q, _) = m.position_flat(&[x], guess, &cfg).unwrap_or_else(|e| panic!("phi {x} at {k:e}: {e}"));
                let kin = m.kinematics_flat(&[x], guess, &cfg).unwrap_or_else(|e| panic!("phi {x} at {k:e}: {e}"));
                let off = (0..2).fold(0.0f64, |o, u| o.max((q[u] - base[u]).abs()).max((kin.q[u] - base[u]).abs()));
                if off > TOL {
                    wrong.push(format!("phi {x:.3} from {guess:?} at {k:e}: {q:?}, size 1 {base:?}"));
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{} solves in another mode than size 1's:\n{}", wrong.len(), wrong.join("\n"));
}
/// The gear-lever's polar length (`PolarPin`: the pin at distance `s` and angle `phi`) keeps
/// size 1's root from guesses of either sign of `s`: its closed form takes the root `(s, phi)`
/// or `(-s, phi + pi)` whose length has the guess's sign (the sign of the block's determinant,
/// `s` times a constant). From 32 guesses (`s` of `±3.3` or `±0.5` times the size, `phi` every
/// 0.75 rad) at 12 inputs and the 6 sizes of [`SIZES`], 1650 of 2304 solves differed from size
/// 1: the positions alone took an overflowed square for a direction at `1e160` and beyond (see
/// `positions_alone_of_a_polar_length_solve_at_every_scale`), and with that mended, the
/// rescue's Newton still reached the other root in 996. It now mirrors such a block onto the
/// closed form's root, as it does a dyad.
#[test]
fn a_polar_length_keeps_the_sign_of_its_guess() {
    use crate::extreme_scales::PolarPin;
    let cfg = NewtonConfig::default();
    let at = |k: f64| PolarPin { l_c: 2.0 * k, l_p: 1.3 * k, u: 3.0 };
    let one = at(1.0);
    let mut wrong = Vec::new();
    for i in 0..12 {
        let x = [-3.0 + 0.5 * f64::from(i) + 0.01];
        for s in [3.3, -3.3, 0.5, -0.5] {
            for j in 0..8 {
                let guess = [s, -3.0 + 0.75 * f64::from(j)];
                let (base, _) = one.position_flat(&x, &guess, &cfg).unwrap_or_else(|e| panic!("size 1: {e}"));
                for k in SIZES {
                    let m = at(k);
                    let (q, _) = m
                        .position_flat(&x, &[s * k, guess[1]], &cfg)
                        .unwrap_or_else(|e| panic!("phi {} from {guess:?} at {k:e}: {e}", x[0]));
                    // The pin's coordinates rounded, and the angle's rounding over the
                    // pin's distance: a few ulps. The other root is `2 |s|` and `pi` away.
                    if !((q[0] / k - base[0]).abs() <= TOL && (q[1] - base[1]).abs() <= TOL) {
                        wrong.push(format!("phi {} from {guess:?} at {k:e}: {q:?}, size 1 {base:?}", x[0]));
                    }
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{} solves in another root than size 1's:\n{}", wrong.len(), wrong.join("\n"));
}

kinloop::mechanism! {
    /// An ellipse `x^2 + 4 y^2 = 4 r^2` and a circle of radius `rho` about `(t, 0)`: four
    /// intersections, solved by Newton in one block of two lengths.
    pub struct EllipseCircle {
        params r = 1, rho = 1.6;
        input t;
        unknowns x = 1.5 * r, y = 0.5 * r;
        eq ellipse: x * x + 4 * y * y == 4 * r * r;
        eq circle: (x - t) * (x - t) + y * y == rho * rho;
    }
}

/// The assembly modes of a Newton block of lengths are the same four at every size, against
/// the closed form (`3 x^2 - 8 t x + 4 t^2 - 4 rho^2 + 4 r^2 = 0`, `y = ±sqrt(rho^2 - (x -
/// t)^2)`): measured in absolute terms, the test of two modes being one took the four for two
/// at size 1e-9 (every length within 1e-7 of the others), and the starts spread a few units
/// of length around the guess whatever the mechanism's size.
#[test]
fn a_newton_block_of_lengths_has_its_four_modes_at_every_size() {
    let (r, rho, t) = (1.0f64, 1.6f64, 0.3f64);
    let disc = (64.0 * t * t - 12.0 * (4.0 * t * t - 4.0 * rho * rho + 4.0 * r * r)).sqrt();
    let exact: Vec<[f64; 2]> = [(8.0 * t + disc) / 6.0, (8.0 * t - disc) / 6.0]
        .into_iter()
        .flat_map(|x: f64| {
            let y = (rho * rho - (x - t) * (x - t)).sqrt();
            [[x, y], [x, -y]]
        })
        .collect();
    for k in [1e-100, 1e-9, 1e-6, 1.0, 1e6, 1e100] {
        let m = EllipseCircle { r: r * k, rho: rho * k };
        let modes = m.assembly_modes(t * k).unwrap_or_else(|e| panic!("size {k:e}: {e}"));
        let found: Vec<[f64; 2]> = modes.iter().map(|s| [s.q.x / k, s.q.y / k]).collect();
        assert_eq!(found.len(), 4, "size {k:e}: {found:?}");
        for e in &exact {
            assert!(
                found.iter().any(|f| (f[0] - e[0]).abs() < 1e-12 && (f[1] - e[1]).abs() < 1e-12),
                "size {k:e}: {e:?} not among {found:?}"
            );
        }
    }
}
