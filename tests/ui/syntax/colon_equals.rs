kinloop::mechanism! {
    /// `:=` for `=`, as in Pascal or Go.
    pub struct Cam {
        params h := 0.02;
        input phi;
        unknowns s;
        eq lift: s == h * phi;
        point p := (s, 0);
    }
}

fn main() {}
