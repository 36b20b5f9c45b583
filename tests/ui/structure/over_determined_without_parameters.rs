// The same slider position given twice by constants: no parameter to turn into an unknown.
kinloop::mechanism! {
    pub struct Cam {
        input phi;
        unknowns x = 1;
        eq lift: x == 2 + 0.5 * sin(phi);
        eq again: x == 2.5 + 0.5 * sin(phi);
    }
}

fn main() {}
