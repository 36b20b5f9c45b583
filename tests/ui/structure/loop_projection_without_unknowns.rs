kinloop::mechanism! {
    pub struct SliderCrank {
        params r, e;
        input phi;
        unknowns x;
        // The slider's y is given, so the y projection involves no unknown.
        loop oab: r @ phi == (x, e);
    }
}

fn main() {}
