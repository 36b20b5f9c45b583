// An unknown that an `eq` sets to an angle (`y == 2 * psi`) but that is written as a length
// elsewhere (a coordinate of a point) is a length: the `eq` is told, and so is a body turning
// with it, which says why the `eq` makes it no angle.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, m, j;
        input phi;
        unknowns psi, x, y;
        loop oab: r @ phi == (x, 0) + l @ psi;
        eq double: y == 2 * psi;
        point p = (x, y);
        body rod: mass m, com (x, 0), inertia j, turns y;
    }
}

fn main() {}
