kinloop::mechanism! {
    /// A product written as in a textbook, without `*`: `h (...)` reads as a call of `h`.
    pub struct Cam {
        params h = 0.02, r = 0.1;
        input phi;
        unknowns s;
        eq lift: s == h (1 - cos(phi)) + r;
    }
}

fn main() {}
