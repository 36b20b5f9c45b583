//! Angles are radians everywhere; `deg(x)` in a declaration and `kinloop::deg(x)` in Rust convert
//! degrees, checked against closed forms.

use std::f64::consts::FRAC_PI_6;

use crate::support::tol;

kinloop::mechanism! {
    /// A slider driven by a crank set 30 degrees ahead of the input angle.
    pub struct Ahead {
        params r;
        input phi;
        unknowns x = r;
        eq e: x == r * cos(phi + deg(30));
        output lead = deg(30);
    }
}

#[test]
fn declared_degrees_are_radians_in_results() {
    let m = Ahead { r: 2.0 };
    for k in 0..12 {
        let phi = kinloop::deg(30.0 * k as f64);
        let s = m.solve(phi).unwrap();
        // Closed forms: x = r cos(phi + pi/6), dx/dphi = -r sin(phi + pi/6),
        // d2x/dphi2 = -r cos(phi + pi/6); a few ulps of r.
        let t = phi + FRAC_PI_6;
        assert_close!(s.q.x, 2.0 * t.cos(), tol::ULPS, "{k}");
        assert_close!(s.dq.x, -2.0 * t.sin(), tol::ULPS, "{k}");
        assert_close!(s.d2q.x, -2.0 * t.cos(), tol::ULPS, "{k}");
        // The declaration's conversion and the runtime's are the same, bit for bit.
        assert_eq!(s.out.lead.to_bits(), kinloop::deg(30.0).to_bits());
        assert_close!(s.out.lead, FRAC_PI_6, <= f64::EPSILON * FRAC_PI_6);
    }
    assert_close!(kinloop::to_deg(m.solve(kinloop::deg(45.0)).unwrap().flat.x[0]), 45.0, tol::SOLVE);
}
