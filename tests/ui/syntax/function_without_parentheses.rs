kinloop::mechanism! {
    /// Functions applied as in a textbook, without parentheses.
    pub struct Cam {
        params h = 0.02;
        input phi;
        unknowns s, t;
        eq lift: s == h * sin phi;
        eq turn: cos phi == t;
        output w = h * sqrt 2;
    }
}

fn main() {}
