kinloop::mechanism! {
    pub struct FourBar {
        params a, b, c, d, e;
        input phi;
        unknowns beta, gamma, x;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        eq abcd: x == e * cos(beta);
    }
}

fn main() {}
