// An angle in degrees written with the degree sign: not valid Rust, so the compiler rejects it
// before the macro sees it; the language writes `deg(30)`.
kinloop::mechanism! {
    pub struct Tilted {
        params r;
        input phi;
        unknowns x = r;
        eq e: x == r * cos(phi + 30°);
    }
}

fn main() {}
