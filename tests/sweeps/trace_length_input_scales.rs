//! A trace driven by a length input at every size. The slider-driven crank (crank `r` about the
//! origin, rod `l` to a slider pin at `(x, e)`, the pin's travel `x` the input) has limit
//! positions where crank and rod lie in line, `|(x, e)| = l - r` and `l + r`: its curve over
//! `x > 0` is closed, the input reversing at `x = sqrt((l -+ r)^2 - e^2)`. Its loop equations are
//! homogeneous of degree one in the lengths, so the same mechanism `k` times as large has the
//! same angles, at `k` times the inputs.
//!
//! A trace returns positions alone; the acceleration analogs by a length input (about
//! `1 / k^2`) leave `f64` below a size of about `1e-154`, where the first point solve's
//! kinematics failed as not finite and the trace with it, though it needs none of them.
//!
//! Tolerances: a limit position's input within `tol::LOCATED` (relative to the size) of the
//! closed form's; each point on the loop to `tol::SOLVE` of the size (a corrected Newton
//! solution, the residual relative to the equations' magnitudes, about the size); each point's
//! angles within [`ANGLES`] of size 1's, the same steps taken in the same scaled coordinates.

use kinloop::TraceConfig;

use crate::support::tol;

kinloop::mechanism! {
    /// A crank `r` at `phi` about the origin and a rod `l` at `psi` to a slider pin at
    /// `(x, e)`, driven by the slider's travel `x`.
    pub struct SliderDriven {
        params r, l, e;
        input x;
        unknowns phi = 0.5, psi = 3.0;
        loop oab: r @ phi == (x, e) + l @ psi;
    }
}

/// The crank, rod and offset at size 1.
const DIMS: [f64; 3] = [1.0, 2.0, 0.5];

/// Size 1 (the reference) first, then sizes where the acceleration analogs leave `f64` (below
/// about `1e-154`) and beyond the closed forms' sizes on the other side.
const SIZES: [f64; 7] = [1.0, 1e-155, 1e-160, 1e-200, 1e-300, 1e160, 1e300];

/// How far a point's angles may lie from size 1's: both are corrected Newton solutions of the
/// same step in the same scaled coordinates, where the augmented Jacobian is regular, so each is
/// pinned by the residual tolerance (`1e-12`, relative to the equations' magnitudes) to about
/// that (measured: within 7.1e-15 at every size here).
const ANGLES: f64 = 1e-12;

#[test]
fn a_length_driven_trace_lists_its_limit_positions_at_every_size() {
    let [r, l, e] = DIMS;
    let limits = [((l - r) * (l - r) - e * e).sqrt(), ((l + r) * (l + r) - e * e).sqrt()];
    let mut reference: Option<Vec<[f64; 2]>> = None;
    for k in SIZES {
        let m = SliderDriven { r: r * k, l: l * k, e: e * k };
        let x0 = 1.5 * k;
        let g = m.position(x0, &m.guess(x0)).unwrap_or_else(|err| panic!("size {k:e}: {err}")).0;
        let t =
            m.trace_curve(x0, -10.0 * k, &g, &TraceConfig::default()).unwrap_or_else(|err| panic!("size {k:e}: {err}"));
        assert!(t.closed && !t.truncated, "size {k:e}: {} points", t.points.len());
        let mut folds: Vec<f64> = t.folds.iter().map(|f| f.x[0] / k).collect();
        folds.sort_by(f64::total_cmp);
        assert_eq!(folds.len(), 2, "size {k:e}: {folds:?}");
        for (f, lim) in folds.iter().zip(limits) {
            assert!((f - lim).abs() <= tol::LOCATED, "size {k:e}: a limit position at {f}, not {lim}");
        }
        for p in &t.points {
            let ([phi, psi], x) = (p.q, p.x[0] / k);
            let gap = [r * phi.cos() - x - l * psi.cos(), r * phi.sin() - e - l * psi.sin()];
            assert!(gap.iter().all(|g| g.abs() <= tol::SOLVE * (r + l)), "size {k:e}: off the loop at {x}: {gap:?}");
        }
        let angles: Vec<[f64; 2]> = t.points.iter().map(|p| p.q).collect();
        match &reference {
            None => reference = Some(angles),
            Some(at_one) => {
                assert_eq!(angles.len(), at_one.len(), "size {k:e}: points against size 1's");
                let off = angles.iter().zip(at_one).flat_map(|(a, b)| [a[0] - b[0], a[1] - b[1]]);
                let off = off.fold(0.0f64, |m, d| m.max(d.abs()));
                eprintln!("size {k:e}: angles within {off:.1e} of size 1's");
                assert!(off <= ANGLES, "size {k:e}: angles {off:e} from size 1's");
            }
        }
    }
}
