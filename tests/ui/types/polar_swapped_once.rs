// One error per mistake: the swapped term `psi @ l` (for `l @ psi`) makes `l` an angle only by
// that mistake. The coordinate and the sum that use `l` as the length it is were refused too,
// as consequences of the one swap; only the swap is told.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + psi @ l;
        point mid = r @ phi + 0.5 * l @ psi;
        point end = (x, 2 * l);
        let reach = x + l;
        output ahead = reach;
    }
}

fn main() {}
