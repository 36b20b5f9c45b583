kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, gen;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {
    // The mechanism's type is still defined next to the error: no secondary error here.
    let _m: Option<SliderCrank> = None;
}
