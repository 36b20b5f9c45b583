kinloop::mechanism! {
    /// An equation written with `=`.
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi = (x, 0) + l @ psi;
    }
}

fn main() {}
