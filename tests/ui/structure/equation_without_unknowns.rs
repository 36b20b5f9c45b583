kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        eq offset: e == r / 2;
    }
}

fn main() {}
