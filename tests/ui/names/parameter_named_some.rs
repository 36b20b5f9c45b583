kinloop::mechanism! {
    pub struct SliderCrank {
        params r, Some, Ok;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + Some @ psi + (Ok, 0);
    }
}

fn main() {}
