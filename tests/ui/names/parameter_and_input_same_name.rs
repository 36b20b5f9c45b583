kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, phi;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
