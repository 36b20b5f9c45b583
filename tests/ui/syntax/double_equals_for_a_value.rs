kinloop::mechanism! {
    /// A value given with the `==` of an equation: a default, a guess and an input's.
    pub struct SliderCrank {
        params r == 1.0, l = 3.0;
        input phi == 0.5;
        unknowns psi == 0, x = 4;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
