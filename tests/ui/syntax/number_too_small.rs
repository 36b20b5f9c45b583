kinloop::mechanism! {
    /// A literal below the smallest f64, which would read as zero.
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi = 0.5, x;
        loop oab: r @ phi == (x, 1e-400) + l @ psi;
    }
}

fn main() {}
