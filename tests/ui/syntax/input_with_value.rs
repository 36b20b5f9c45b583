kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi = 0.5;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
