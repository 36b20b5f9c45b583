kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: (r, 0) @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
