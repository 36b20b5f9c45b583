kinloop::mechanism! {
    /// A cast, as in Rust code: every value is an f64 already.
    pub struct Cam {
        params h = 0.02;
        input phi;
        unknowns s;
        eq lift: s == h * (phi as f64);
    }
}

fn main() {}
