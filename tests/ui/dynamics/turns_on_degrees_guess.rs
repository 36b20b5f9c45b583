// A pinion's angle, an unknown known as an angle only from its guess in degrees: its centre of
// mass refuses `w` as an angle, and a body turning with it, refused as "not an angle", is
// accepted. The centre of mass is the one error.
kinloop::mechanism! {
    pub struct RackAndPinion {
        params r, l, e, m, j;
        input phi;
        unknowns psi, x, w = deg(30);
        loop oab: r @ phi == (x, e) + l @ psi;
        eq roll: x == r * w;
        body pinion: mass m, com (w, e), inertia j, turns w;
        torque drive on w = 1.0;
    }
}

fn main() {}
