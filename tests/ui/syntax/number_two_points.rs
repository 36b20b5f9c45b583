kinloop::mechanism! {
    pub struct FourBar {
        params a = 1.0.0, b = 3, c = 2.5, d = 3.2;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

fn main() {}
