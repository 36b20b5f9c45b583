kinloop::mechanism! {
    /// Rust keywords called as functions: each is said to be a keyword and no function, with the
    /// built-ins that do a conditional's work; it said "found `if`".
    pub struct SliderCrank {
        params r = 1, l = 3;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        output a = if(x);
        output b = fn(x);
        output c = 2 * match(x, 1);
    }
}

fn main() {}
