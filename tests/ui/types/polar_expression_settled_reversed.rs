// `(2 * psi) @ l` before `0.5 * l @ psi`, and `psi` the argument of a sine: as
// `polar_expression_settled` in the other order, the wrong term alone is told.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + (2 * psi) @ l;
        point p = (x, 0) + 0.5 * l @ psi;
        output lean = sin(psi);
    }
}

fn main() {}
