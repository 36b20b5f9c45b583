// `l @ psi` beside `psi @ l`, and `l` a coordinate of a point: `l` is the length, so
// `psi @ l` is the wrong term. A coordinate told nothing to two bare terms (a tie), where it
// settles two expression terms; it settles both alike.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + l @ psi;
        point p = (x, 0) + psi @ l;
        point q = (x, 2 * l);
    }
}

fn main() {}
