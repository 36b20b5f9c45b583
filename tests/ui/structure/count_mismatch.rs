kinloop::mechanism! {
    /// One loop (two equations) for three unknowns.
    pub struct FourBar {
        params a, b, c, d;
        input phi;
        unknowns beta, gamma, delta;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma + c @ delta;
    }
}

fn main() {}
