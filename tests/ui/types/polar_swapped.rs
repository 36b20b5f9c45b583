kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + psi @ l;
        point mid = r @ phi + 0.5 * l @ psi;
    }
}

fn main() {}
