//! The numbers the `cam_linkage` example prints about the rocker's swing and the slider's
//! stroke: the extremes it locates along the sweep, and the limit positions of the equivalent
//! four-bar it sets beside them (values and cam angles), against a brute-force search of the
//! drive's position written here from its geometry: the roller centre P where the circle of
//! radius `r_cam + r_roller` about the cam centre C = e (cos phi, sin phi) meets the circle of
//! radius `l_arm` about the pivot A (on the left of A -> C, the declared assembly mode), the
//! rocker angle that of A -> P, the slider at the rod's length from the pin Q on its guide.
//! Checked for the drive of the example and for one of other proportions.

// The example's own functions, so that what is checked is what it prints (its `main` and its
// chart writing are not called here).
#[allow(dead_code)]
#[path = "../cam_linkage.rs"]
mod cam_linkage;

mod turn_search;

use cam_linkage::extremes;
use kinloop_fixtures::cam_linkage::CamLinkage;
use turn_search::{angle_gap, smallest};

/// The example's drive and one with a larger eccentricity, a shorter arm and another bell-crank
/// angle (still a crank-rocker: `e + |OA| = 95.4 <= r_cam + r_roller + l_arm = 103`).
fn drives() -> [CamLinkage; 2] {
    [
        CamLinkage::default(),
        CamLinkage {
            e: 14.0,
            r_cam: 38.0,
            r_roller: 10.0,
            a_x: 15.0,
            l_arm: 55.0,
            delta: 2.2,
            ..CamLinkage::default()
        },
    ]
}

/// `(psi, x)` at cam angle `phi`, from the geometry alone.
fn pose(m: &CamLinkage, phi: f64) -> (f64, f64) {
    let (cx, cy) = (m.e * phi.cos(), m.e * phi.sin());
    let (ux, uy) = (cx - m.a_x, cy - m.a_y);
    let d = ux.hypot(uy);
    let (ra, rb) = (m.l_arm, m.r_cam + m.r_roller);
    let along = (ra * ra - rb * rb + d * d) / (2.0 * d);
    let across = (ra * ra - along * along).sqrt();
    let (px, py) = (m.a_x + (along * ux - across * uy) / d, m.a_y + (along * uy + across * ux) / d);
    let psi = (py - m.a_y).atan2(px - m.a_x);
    let (qx, qy) = (m.a_x + m.l_out * (psi + m.delta).cos(), m.a_y + m.l_out * (psi + m.delta).sin());
    (psi, qx + (m.l_rod * m.l_rod - (m.h - qy).powi(2)).sqrt())
}

/// Values to 1e-12 of the swing (in degrees) or of the stroke: at an extreme the quantity is
/// flat, so the search's location error (about `sqrt(eps)` of a radian, golden sections on a
/// flat extremum) enters the value only squared. Cam angles to 1e-5 degrees: that location
/// error, about 1e-8 rad = 6e-7°, with margin.
#[test]
fn the_printed_swing_and_stroke_agree_with_the_drive_s_geometry() -> Result<(), Box<dyn std::error::Error>> {
    for m in drives() {
        let rows = extremes(&m)?;
        let psi = |phi: f64| pose(&m, phi).0.to_degrees();
        let x = |phi: f64| pose(&m, phi).1;
        let (psi_max, psi_min) = (smallest(|phi| -psi(phi)), smallest(psi));
        let (x_max, x_min) = (smallest(|phi| -x(phi)), smallest(x));
        let want = [(psi_max.0, -psi_max.1), psi_min, (x_max.0, -x_max.1), x_min];
        let (swing, stroke) = (want[0].1 - want[1].1, want[2].1 - want[3].1);
        assert!(swing > 1.0 && stroke > 1.0, "the drive moves: {swing}°, {stroke} mm");
        for (k, (row, (at, value))) in rows.iter().zip(want).enumerate() {
            let scale = if k < 2 { swing } else { stroke };
            let what = format!("{} of {m:?}", row.name);
            assert!((row.value - value).abs() <= 1e-12 * scale, "{what}: located {} vs {value}", row.value);
            assert!((row.closed - value).abs() <= 1e-12 * scale, "{what}: closed form {} vs {value}", row.closed);
            assert!(angle_gap(row.at, at) <= 1e-5, "{what}: located at {}° vs {at}°", row.at);
            assert!(angle_gap(row.closed_at, at) <= 1e-5, "{what}: closed form at {}° vs {at}°", row.closed_at);
        }
    }
    Ok(())
}
