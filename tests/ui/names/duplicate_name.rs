kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, r;
        loop oab: r @ phi == (r, 0) + l @ psi;
    }
}

fn main() {}
