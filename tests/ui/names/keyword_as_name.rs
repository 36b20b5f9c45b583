// Rust keywords where names belong: each is named as a keyword, with a name to write instead
// (the raw identifier, `r#type`, is accepted too).
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, in;
        input phi;
        unknowns psi, x, type;
        loop oab: r @ phi == (x, 0) + l @ psi;
        let mut gap = x - r;
        output match = x;
    }
}

fn main() {}
