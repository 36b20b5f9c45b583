//! The strokes and phase shifts the `rhombic_variants` example prints for paper 000's Figs. 2
//! and 3 against the drives built triangle by triangle (`docs/papers.md`): the crank pin B,
//! then the pin on the line its rod reaches from B (the displacer F on y = de to the right, the
//! piston C on the X axis to the left), the rigid rod's third joint D, and the other pin from D;
//! searched by brute force over the turn, never solved by kinloop.

// The example's own functions, so that what is checked is what it prints (its `main` and its
// chart writing are not called here).
#[allow(dead_code)]
#[path = "../rhombic_variants.rs"]
mod rhombic_variants;

mod turn_search;

use kinloop_fixtures::{DisplacerRodDrive, WorkingRodDrive};
use rhombic_variants::report;
use std::f64::consts::TAU;
use turn_search::smallest;

/// Fig. 2 at crank angle `phi`: `(X_C, X_F)`. F to the right of B at `l_b`, D on the rigid rod,
/// C to the left of D at `l_p`.
fn fig2(m: &DisplacerRodDrive, phi: f64) -> (f64, f64) {
    let (bx, by) = (m.r * phi.cos(), m.e_p + m.r * phi.sin());
    let x_f = bx + (m.l_b * m.l_b - (by - m.de).powi(2)).sqrt();
    let phi4 = (by - m.de).atan2(bx - x_f);
    let (dx, dy) = (x_f + m.l_fd * (phi4 + m.gamma_b).cos(), m.de + m.l_fd * (phi4 + m.gamma_b).sin());
    (dx - (m.l_p * m.l_p - dy * dy).sqrt(), x_f)
}

/// Fig. 3 at crank angle `phi`: `(X_C, X_F)`. C to the left of B at `l_p`, D on the rigid rod,
/// F to the right of D at `l_b`.
fn fig3(m: &WorkingRodDrive, phi: f64) -> (f64, f64) {
    let (bx, by) = (m.r * phi.cos(), m.e_p + m.r * phi.sin());
    let x_c = bx - (m.l_p * m.l_p - by * by).sqrt();
    let phi2 = by.atan2(bx - x_c);
    let (dx, dy) = (x_c + m.l_cd * (phi2 + m.gamma_p).cos(), m.l_cd * (phi2 + m.gamma_p).sin());
    (x_c, dx + (m.l_b * m.l_b - (dy - m.de).powi(2)).sqrt())
}

/// `[piston stroke, displacer stroke, outer phase shift, inner phase shift]` of a drive whose
/// positions are `pos`: outer from the piston's smallest X_C to the displacer's largest X_F,
/// inner from the largest X_C to the smallest X_F (degrees in `[0, 360)`).
fn searched(pos: impl Fn(f64) -> (f64, f64)) -> [f64; 4] {
    let (c_min, c_max) = (smallest(|p| pos(p).0), smallest(|p| -pos(p).0));
    let (f_min, f_max) = (smallest(|p| pos(p).1), smallest(|p| -pos(p).1));
    [
        -c_max.1 - c_min.1,
        -f_max.1 - f_min.1,
        (f_max.0 - c_min.0).rem_euclid(360.0),
        (f_min.0 - c_max.0).rem_euclid(360.0),
    ]
}

/// Strokes to 1e-12 of themselves (at an extreme the position is flat, so the search's location
/// error, about 1e-8 rad, enters it only squared); phase shifts to 2e-5 degrees (that location
/// error at both ends, 6e-7° each, with margin).
fn check(what: &str, printed: [f64; 4], want: [f64; 4]) {
    for s in 0..2 {
        assert!((printed[s] - want[s]).abs() <= 1e-12 * want[s], "{what}: stroke {} vs {}", printed[s], want[s]);
    }
    for s in 2..4 {
        let gap = (printed[s] - want[s]).rem_euclid(360.0);
        assert!(gap.min(360.0 - gap) <= 2e-5, "{what}: phase shift {}° vs {}°", printed[s], want[s]);
    }
}

#[test]
fn the_printed_strokes_and_phase_shifts_agree_with_the_triangles() -> Result<(), Box<dyn std::error::Error>> {
    let other2 = DisplacerRodDrive { l_fd: 2.8, gamma_b: -0.5, l_p: 3.4, de: 0.6, ..DisplacerRodDrive::default() };
    for m in [DisplacerRodDrive::default(), other2] {
        let turn = m.sampled(0.0, TAU, 361, &m.guess(0.0))?;
        let printed = report("Fig. 2", &turn, [DisplacerRodDrive::COL.x_c, DisplacerRodDrive::COL.x_f])?;
        check(&format!("{m:?}"), printed, searched(|p| fig2(&m, p)));
    }
    let other3 = WorkingRodDrive { l_cd: 2.3, gamma_p: 0.3, l_b: 3.0, de: 0.2, ..WorkingRodDrive::default() };
    for m in [WorkingRodDrive::default(), other3] {
        let turn = m.sampled(0.0, TAU, 361, &m.guess(0.0))?;
        let printed = report("Fig. 3", &turn, [WorkingRodDrive::COL.x_c, WorkingRodDrive::COL.x_f])?;
        check(&format!("{m:?}"), printed, searched(|p| fig3(&m, p)));
    }
    Ok(())
}
