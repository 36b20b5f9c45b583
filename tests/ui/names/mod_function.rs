// `mod(x, period)`, as other languages write a remainder: an unsupported function, with the
// built-in to write instead (`mod` is a Rust keyword, and was "expected a value, found `mod`").
kinloop::mechanism! {
    pub struct Cam {
        params h = 0.02;
        input phi;
        unknowns s;
        eq lift: s == h * sin(mod(phi, 2 * pi));
    }
}

fn main() {}
