kinloop::mechanism! {
    /// A four-bar with a third unknown that stands on both sides of its equation: the terms in
    /// `x` cancel, so the equation relates `d` and `c` alone.
    pub struct FourBar {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, x;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        eq slide: x + d == c + x;
    }
}

fn main() {}
