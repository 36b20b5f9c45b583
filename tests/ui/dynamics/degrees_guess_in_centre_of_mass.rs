// A pinion's angle, an unknown known as an angle only from its guess in degrees (the kinematics
// rolls it into a length, `x == r * w`), bare in a centre of mass: it compiled, the pinion's
// mass placed `w` radians along x, as other angles in a centre of mass are refused.
kinloop::mechanism! {
    pub struct RackAndPinion {
        params r, l, e, m;
        input phi;
        unknowns psi, x, w = deg(30);
        loop oab: r @ phi == (x, e) + l @ psi;
        eq roll: x == r * w;
        body pinion: mass m, com (w, e);
    }
}

fn main() {}
