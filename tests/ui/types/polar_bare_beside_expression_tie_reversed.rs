// `(2 * psi) @ l` before `l @ psi`: as `polar_bare_beside_expression_tie`, in the other order,
// one error at the first written, naming both readings.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + (2 * psi) @ l;
        point p = (x, 0) + l @ psi;
    }
}

fn main() {}
