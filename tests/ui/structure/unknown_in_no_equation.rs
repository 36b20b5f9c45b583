kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x, s;
        loop oab: r @ phi == (x, 0) + l @ psi;
        output rod_end = x + s;
    }
}

fn main() {}
