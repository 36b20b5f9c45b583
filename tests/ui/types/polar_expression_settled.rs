// `0.5 * l @ psi` beside `(2 * psi) @ l`, and `psi` the argument of a sine: `psi` is the
// angle, so `(2 * psi) @ l` is the wrong term. The first written was blamed (here the right
// one, with "`psi` is an angle too"), beside the wrong one; the wrong one alone is told.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + 0.5 * l @ psi;
        point p = (x, 0) + (2 * psi) @ l;
        output lean = sin(psi);
    }
}

fn main() {}
