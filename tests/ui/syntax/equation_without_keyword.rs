// Equations written without `eq` or `loop` and a name.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi = 0.5, x = 4.0, u;
        c: r @ phi == (x, 0) + l @ psi;
        u == 2 * x;
    }
}

fn main() {}
