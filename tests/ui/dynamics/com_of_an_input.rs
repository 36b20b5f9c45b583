kinloop::mechanism! {
    // The input `s` in the centre of mass: the mass model reads unknowns, outputs and constants,
    // so the point is declared (`point p = (s, 0);`) and named (`com p`).
    pub struct Slide {
        params a = 1.0;
        input s;
        unknowns x = 0.5;
        eq e: x == a * s;
        body block: mass 1.0, com (s, 0);
    }
}

fn main() {}
