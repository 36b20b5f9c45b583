// An unknown that an `eq` sets to an angle (`y == 2 * psi`) is an angle: beside a length it
// changes with the unit of length.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x, y;
        loop oab: r @ phi == (x, 0) + l @ psi;
        eq double: y == 2 * psi;
        output w = y + x;
    }
}

fn main() {}
