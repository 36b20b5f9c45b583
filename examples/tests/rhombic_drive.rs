//! The numbers the main job (`rhombic_drive` example) prints about the pistons' dead centres:
//! the extreme positions it locates, the closed forms and crank angles it sets beside them, and
//! the phase shifts, against a brute-force search of paper 000's published position formulas
//! (`docs/papers.md`): `X_C = L_P (lambda_P cos phi1 - cos phi2)` with
//! `sin phi2 = lambda_P (k_P + sin phi1)`, `cos phi2 > 0`, and `X_F` likewise with
//! `cos phi4 < 0`, scanned over the turn and refined by golden sections. Neither the library's
//! root finding nor the example's stretched-and-folded geometry enters the reference. Checked
//! for the gallery's drive and for a second one with other lengths, offsets and arm angle.

// The example's own functions, so that what is checked is what it prints (its `main` and its
// chart writing are not called here).
#[allow(dead_code)]
#[path = "../rhombic_drive.rs"]
mod rhombic_drive;

mod turn_search;

use kinloop_fixtures::RhombicDrive;
use rhombic_drive::extremes;
use turn_search::{angle_gap, smallest};

/// The gallery's drive and one with other proportions (a larger displacer offset, arms nearly
/// square, the crank centre below the piston's line).
fn drives() -> [RhombicDrive; 2] {
    [
        RhombicDrive::default(),
        RhombicDrive {
            r_p: 1.3,
            r_b: 0.9,
            l_p: 4.2,
            l_b: 3.1,
            e_p: -0.4,
            de: 0.6,
            gamma: 1.9,
            ..RhombicDrive::default()
        },
    ]
}

/// Paper 000's closed form: `(X_C, X_F)` at crank angle `phi1`.
fn published(m: &RhombicDrive, phi1: f64) -> (f64, f64) {
    let (lam_p, lam_b) = (m.r_p / m.l_p, m.r_b / m.l_b);
    let (k_p, k_b) = (m.e_p / m.r_p, (m.e_p - m.de) / m.r_b);
    let s2 = lam_p * (k_p + phi1.sin());
    let s4 = lam_b * (k_b + (phi1 + m.gamma).sin());
    let (c2, c4) = ((1.0 - s2 * s2).sqrt(), -(1.0 - s4 * s4).sqrt());
    (m.l_p * (lam_p * phi1.cos() - c2), m.l_b * (lam_b * (phi1 + m.gamma).cos() - c4))
}

/// The located and the closed-form extremes against the brute-force search. Values to 1e-12 of
/// the stroke: at an extreme the position is flat, so the search's location error (about
/// `sqrt(eps)` of a radian, golden sections on a flat minimum) enters the value only squared.
/// Crank angles to 1e-5 degrees: that location error, about 1e-8 rad = 6e-7°, with margin.
#[test]
fn the_printed_dead_centres_agree_with_the_published_position_formulas() -> Result<(), Box<dyn std::error::Error>> {
    for m in drives() {
        let e = extremes(&m)?;
        let x_c = |phi: f64| published(&m, phi).0;
        let x_f = |phi: f64| published(&m, phi).1;
        let (c_min, c_max) = (smallest(x_c), smallest(|phi| -x_c(phi)));
        let (f_max, f_min) = (smallest(|phi| -x_f(phi)), smallest(x_f));
        let want = [c_min, (c_max.0, -c_max.1), (f_max.0, -f_max.1), f_min];
        let strokes = [want[1].1 - want[0].1, want[2].1 - want[3].1];
        for (row, (at, value)) in e.rows.iter().zip(want) {
            let scale = if row.name.starts_with("X_C") { strokes[0] } else { strokes[1] };
            let what = format!("{} of {m:?}", row.name);
            assert!((row.value - value).abs() <= 1e-12 * scale, "{what}: located {} vs {value}", row.value);
            assert!((row.closed - value).abs() <= 1e-12 * scale, "{what}: closed form {} vs {value}", row.closed);
            assert!(angle_gap(row.at, at) <= 1e-5, "{what}: located at {}° vs {at}°", row.at);
            assert!(angle_gap(row.closed_at, at) <= 1e-5, "{what}: closed form at {}° vs {at}°", row.closed_at);
        }
        // Outer to outer (piston's smallest X_C to displacer's largest X_F), inner to inner.
        let shifts = [(want[2].0 - want[0].0).rem_euclid(360.0), (want[3].0 - want[1].0).rem_euclid(360.0)];
        for ((located, closed), want) in e.shift.into_iter().zip(e.closed_shift).zip(shifts) {
            assert!(
                angle_gap(located, want) <= 2e-5 && angle_gap(closed, want) <= 2e-5,
                "{located}, {closed} vs {want}"
            );
        }
    }
    Ok(())
}
