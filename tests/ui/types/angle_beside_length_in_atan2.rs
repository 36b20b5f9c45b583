// `atan2`, `hypot` and `wrap` of an angle and a length change with the unit of length, as their
// sum would.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        output heading = atan2(x, psi);
        output turns = wrap(x, phi);
    }
}

fn main() {}
