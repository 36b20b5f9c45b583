// `psi @ l` beside `th @ psi`, `th` the argument of a sine: swapping `th @ psi` makes both
// terms right (`psi` a length turned by `l` and by `th`), where swapping `psi @ l` would leave
// the angle `th` as a length. Both terms were told; only the swap that mends both is.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e, th;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + psi @ l;
        point p = (x, 0) + th @ psi;
        output lean = sin(th);
    }
}

fn main() {}
