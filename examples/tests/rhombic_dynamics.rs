//! The reduced inertia, its slope, the gas load and the driving torque the `rhombic_dynamics`
//! example prints every 30 degrees at 1500 rpm, and the mean driving torque, against the drive
//! written out from its loops (`docs/papers.md`, paper 000) and its declared bodies and gas force,
//! never solved by kinloop: `sin phi2 = (e_p + r_p sin phi) / l_p` (`phi2` near 0),
//! `X_C = r_p cos phi - l_p cos phi2`, `sin phi4 = (e_p + r_b sin(phi + gamma) - de) / l_b`
//! (`phi4` near pi), `X_F = r_b cos(phi + gamma) - l_b cos phi4`, their analogs differentiated by
//! hand (`phi2' = r_p cos phi / (l_p cos phi2)`, `X_C' = -r_p sin phi + l_p sin phi2 phi2'`, and
//! alike), `J = sum m |v_S'|^2 + J_S w'^2` over the five bodies, `J'` by central differences,
//! `Q = F X_C'` with the Schmidt pressure of the declaration, and at constant speed
//! `M = 1/2 J' omega^2 - Q`.

// The example's own functions, so that what is checked is what it prints (its `main`, its run-up
// and its chart writing are not called here).
#[allow(dead_code)]
#[path = "../rhombic_dynamics.rs"]
mod rhombic_dynamics;

use kinloop_fixtures::StirlingEngine;
use rhombic_dynamics::hot_cycle;
use std::f64::consts::TAU;

/// `J` and `Q` at crank angle `phi`.
fn written_out(m: &StirlingEngine, phi: f64) -> (f64, f64) {
    let s2 = (m.e_p + m.r_p * phi.sin()) / m.l_p;
    let c2 = (1.0 - s2 * s2).sqrt();
    let w2 = m.r_p * phi.cos() / (m.l_p * c2);
    let (x_c, v_c) = (m.r_p * phi.cos() - m.l_p * c2, -m.r_p * phi.sin() + m.l_p * s2 * w2);
    let t = phi + m.gamma;
    let s4 = (m.e_p + m.r_b * t.sin() - m.de) / m.l_b;
    let c4 = -(1.0 - s4 * s4).sqrt();
    let w4 = m.r_b * t.cos() / (m.l_b * c4);
    let (x_f, v_f) = (m.r_b * t.cos() - m.l_b * c4, -m.r_b * t.sin() + m.l_b * s4 * w4);
    // The bodies' centres: S1 on the crank (speed analog l_as1), S2 on the working rod from C,
    // S4 on the displacer rod from F, the piston at C and the displacer at F.
    let v2 = [v_c - m.l_cs2 * s2 * w2, m.l_cs2 * c2 * w2];
    let v4 = [v_f - m.l_fs4 * s4 * w4, m.l_fs4 * c4 * w4];
    let j = m.m_crank * m.l_as1 * m.l_as1
        + m.j_crank
        + m.m_rod2 * (v2[0] * v2[0] + v2[1] * v2[1])
        + m.j_rod2 * w2 * w2
        + m.m_rod4 * (v4[0] * v4[0] + v4[1] * v4[1])
        + m.j_rod4 * w4 * w4
        + m.m_piston * v_c * v_c
        + m.m_displacer * v_f * v_f;
    let cold = m.dead + m.area * ((x_c - m.x_c_min) + (m.x_f_max - x_f));
    let hot = m.dead + m.area * (x_f - m.x_f_min);
    let force = (m.mass_r / (cold / m.t_cold + hot / m.t_hot) - m.buffer) * m.area;
    (j, force * v_c)
}

/// `J` to 1e-12 of itself and `Q` to 1e-9 of its largest magnitude (closed forms, rounding
/// only; the example prints four significant digits); `J'` and `M` to 1e-7 of their largest
/// magnitudes: central differences with a step of 1e-5 rad, whose truncation error is `h^2 / 6`
/// times the third derivative (of the order of `J'` itself: 2e-11 of it) and whose rounding
/// error is about `1e-16 J / h`; the mean driving torque to 1e-9 of the largest `|Q|`.
#[test]
fn the_printed_inertia_load_and_torque_agree_with_the_drive_written_out() -> Result<(), Box<dyn std::error::Error>> {
    let omega = 1500.0 * TAU / 60.0;
    let (m, cycle) = hot_cycle(omega)?;
    assert_eq!(cycle.points.len(), 3600);
    let h = 1e-5;
    let slope = |phi: f64| (written_out(&m, phi + h).0 - written_out(&m, phi - h).0) / (2.0 * h);
    let q_max = cycle.points.iter().map(|p| written_out(&m, p.phi).1.abs()).fold(0.0, f64::max);
    let dj_max = cycle.points.iter().step_by(10).map(|p| slope(p.phi).abs()).fold(0.0, f64::max);
    let m_max = 0.5 * dj_max * omega * omega + q_max;
    for (k, p) in cycle.points.iter().enumerate() {
        assert!((p.phi - k as f64 * TAU / 3600.0).abs() < 1e-12 && p.omega == omega && p.eps == 0.0, "{p:?}");
        if k % 300 != 0 {
            continue;
        }
        let (j, q) = written_out(&m, p.phi);
        let dj = slope(p.phi);
        let torque = 0.5 * dj * omega * omega - q;
        assert!((p.inertia - j).abs() <= 1e-12 * j, "phi = {}: J {} vs {j}", p.phi, p.inertia);
        assert!((p.load - q).abs() <= 1e-9 * q_max, "phi = {}: Q {} vs {q}", p.phi, p.load);
        assert!((p.inertia_slope - dj).abs() <= 1e-7 * dj_max, "phi = {}: J' {} vs {dj}", p.phi, p.inertia_slope);
        assert!((p.torque - torque).abs() <= 1e-7 * m_max, "phi = {}: M {} vs {torque}", p.phi, p.torque);
    }
    // Over a turn at constant speed `J'` averages to zero: the mean torque is the mean of `-Q`.
    let mean = -cycle.points.iter().map(|p| written_out(&m, p.phi).1).sum::<f64>() / 3600.0;
    let a0 = cycle.torque_harmonics(4)?.a0;
    assert!((a0 - mean).abs() <= 1e-9 * q_max, "mean torque {a0} vs {mean}");
    Ok(())
}
