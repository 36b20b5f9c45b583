kinloop::mechanism! {
    pub struct FourBar {
        params a, b, c, d;
        input phi;
        unknowns beta = NaN, gamma = inf;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

fn main() {}
