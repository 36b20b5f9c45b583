kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        inputs phi, t;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
