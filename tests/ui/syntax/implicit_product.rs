kinloop::mechanism! {
    /// Products written as in a textbook, without `*`.
    pub struct Cam {
        params h = 0.02, r = 0.1;
        input phi;
        unknowns s = 2pi, t;
        eq lift: s == h * (1 - cos(phi));
        eq turn: t == 2(r + h) + phi;
        output w = (r + h) 3;
    }
}

fn main() {}
