// A number without its exponent's digits: the compiler's lexer says so, and the macro's own
// error for the same token says what to write (it said to write the product `1 * e`).
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1e, l = 3;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
