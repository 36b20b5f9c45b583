// `sind` (sine of degrees) is not a function: the hint says how to write degrees.
kinloop::mechanism! {
    pub struct Tilted {
        params r;
        input phi;
        unknowns x = r;
        eq e: x == r * sind(phi);
    }
}

fn main() {}
