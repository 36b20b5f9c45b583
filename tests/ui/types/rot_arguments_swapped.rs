// The vector and the angle of `rot` the other way round: one error that says to swap them.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        point tip = rot(psi, (l, 0));
    }
}

fn main() {}
