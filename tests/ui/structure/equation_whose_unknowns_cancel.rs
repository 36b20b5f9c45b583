kinloop::mechanism! {
    /// A four-bar with a third unknown in an equation whose terms cancel.
    pub struct FourBar {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, x;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        eq slide: beta * 0 + x == x;
    }
}

fn main() {}
