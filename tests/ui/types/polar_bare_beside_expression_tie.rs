// `l @ psi` beside `(2 * psi) @ l`: one bare term, one expression, taking `l` and `psi` in
// opposite roles, and nothing else in the mechanism tells which is the length. The bare term
// was told to swap, where two bare terms and two expression terms get one error naming both
// readings; it gets that error too, at the first written.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + l @ psi;
        point p = (x, 0) + (2 * psi) @ l;
    }
}

fn main() {}
