// `0.5 * l @ psi` and `(2 * psi) @ l` take `l` and `psi` in opposite orders, each length an
// expression, and nothing else in the mechanism tells which is the length. The first written
// was told that its length is an angle, whichever it was; in either order the first is now told
// that the two disagree, with both readings.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + 0.5 * l @ psi;
        point p = (x, 0) + (2 * psi) @ l;
    }
}

fn main() {}
