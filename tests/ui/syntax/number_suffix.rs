kinloop::mechanism! {
    /// A typed literal.
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi = 0.5f32, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
