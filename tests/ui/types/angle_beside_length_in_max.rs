// `max`, `min` and `clamp` return one of their arguments: an angle beside a length there
// changes with the unit of length, as their sum would.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        output reach = max(x, psi);
        output stop = clamp(x, 0, phi);
    }
}

fn main() {}
