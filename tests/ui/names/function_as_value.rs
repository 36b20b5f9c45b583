kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, d;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        output s = sin;
        output thirty = deg;
    }
}

fn main() {}
