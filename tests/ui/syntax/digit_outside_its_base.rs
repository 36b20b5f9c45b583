// A binary number with a digit its base does not have: the compiler's lexer says so, and the
// macro's own error for the same token says which digit (it said to write the product
// `0 * b102`).
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1, l = 0b102;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
