kinloop::mechanism! {
    pub struct Cam {
        params h = 0.02, r = 1.0;
        input phi;
        unknowns s;
        let k = 0 / 0;
        eq lift: s == h * sin(phi) / (r - r) + r / 0;
        output speed = max(k, s);
    }
}

fn main() {}
