kinloop::mechanism! {
    /// A power written as Python writes it.
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi = 0.5, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        output energy = x ** 2;
    }
}

fn main() {}
