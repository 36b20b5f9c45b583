kinloop::mechanism! {
    pub struct SliderCrank {
        params r: f64, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
