kinloop::mechanism! {
    /// A four-bar with its one contour declared twice.
    pub struct FourBar {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        // The same contour again, walked the other way round:
        loop adcb: (d, 0) + c @ gamma - b @ beta == a @ phi;
    }
}

fn main() {}
