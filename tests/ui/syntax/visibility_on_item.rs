// A visibility or another Rust keyword written before an item or a name, as a Rust field is
// written: each is said to be removed (not taken for the name, which would ask to rename `pub`),
// and the names after it keep their fields, so the code below adds no error of its own.
kinloop::mechanism! {
    pub struct SliderCrank {
        pub params r = 1.0, l = 3.0;
        params pub(crate) e = 0.1, const h = 0.2;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e + h) + l @ psi;
        pub point b = r @ phi;
    }
}

fn main() {
    let m = SliderCrank { r: 1.0, l: 3.0, e: 0.1, h: 0.2 };
    let _ = m.r + m.l + m.e + m.h;
}
