kinloop::mechanism! {
    pub struct InvertedSliderCrank {
        params r, d;
        input phi;
        unknowns th = deg(30), s = d;
        loop oab: r @ phi == (d, 0) + th @ s;
    }
}

fn main() {}
