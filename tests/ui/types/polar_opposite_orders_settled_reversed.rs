// `psi @ l` before `l @ psi`, and `l` a coordinate of a point: as
// `polar_opposite_orders_settled` in the other order, the wrong term is told.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + psi @ l;
        point p = (x, 0) + l @ psi;
        point q = (x, 2 * l);
    }
}

fn main() {}
