kinloop::mechanism! {
    /// Four syntax errors, each reported at its place, all at once.
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi = 0f64, x;
        loop r @ phi == (x, 0) + l @ psi;
        eq e: x = 2 * r;
        point p = (x, 0, 0);
    }
}

fn main() {}
