kinloop::mechanism! {
    /// A slider whose position cancels where it is written.
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi = 0.5, x;
        loop oab: r @ phi == (x - x, e) + l @ psi;
    }
}

fn main() {}
