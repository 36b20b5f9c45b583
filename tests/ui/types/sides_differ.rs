kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == x + l * cos(psi);
    }
}

fn main() {}
