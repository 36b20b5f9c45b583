kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        link ab = r @ phi;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
