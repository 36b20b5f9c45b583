// `l @ psi` and `psi @ l` take the same two names in opposite orders, and nothing else in the
// mechanism tells which is the length. The first written was told "the two are swapped",
// whichever it was (in one order, the loop's `l @ psi`); it is told that the two disagree, and
// how to write them alike either way. The coordinate `l + psi` is told nothing more.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + l @ psi;
        point p = (x, 0) + psi @ l;
        point q = (x, l + psi);
    }
}

fn main() {}
