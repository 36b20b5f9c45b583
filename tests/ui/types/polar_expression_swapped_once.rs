// One error per mistake: the term `(2 * psi) @ l` has an angle for its length, and makes `l` an
// angle only by that mistake. The other term, the coordinate and the sum that use `l` as the
// length it is were refused too, as consequences of the one term; only the term is told.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + (2 * psi) @ l;
        point mid = r @ phi + 0.5 * l @ psi;
        point end = (x, 2 * l);
        let reach = x + l;
        output ahead = reach;
    }
}

fn main() {}
