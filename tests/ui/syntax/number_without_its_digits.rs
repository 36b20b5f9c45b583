// An exponent without its digits and a digit its base does not have: the compiler's lexer
// says so, and the macro's own error for the same token says what to write (it said only to
// write the products `1 * e` and `0 * b102`).
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1e, l = 0b102;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
