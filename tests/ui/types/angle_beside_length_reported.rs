// An angle beside a length written straight into the values a mechanism reports: a point whose
// coordinate adds a slider's position and a rod's angle, and an output that subtracts twice
// the angle from the position. Both compiled (where the same sums named by a `let` did not)
// into values that changed with the unit of length.
kinloop::mechanism! {
    pub struct Slider {
        params r = 50.0, l = 200.0;
        input phi;
        unknowns psi = 3.0, x = 250.0;
        loop rod: r @ phi == (x, 0) + l @ psi;
        point p = (x + psi, 0);
        output lead = x - 2 * psi;
    }
}

fn main() {}
