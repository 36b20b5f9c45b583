// `th @ psi` before `psi @ l`, `th` the argument of a sine: as `polar_one_swap_mends_two`
// in the other order, the one swap that mends both terms is told.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e, th;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + th @ psi;
        point p = (x, 0) + psi @ l;
        output lean = sin(th);
    }
}

fn main() {}
