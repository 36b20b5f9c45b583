kinloop::mechanism! {
    pub struct Cam {
        params r#h = 0.02, h = 0.03, r#pi = 3.0;
        input phi;
        unknowns s, r#phi;
        eq lift: s == r#h * sin(phi) + h;
        eq r#lift: s == 2 * h;
    }
}

fn main() {}
