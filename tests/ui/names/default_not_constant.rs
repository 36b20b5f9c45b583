kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3 * r;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
