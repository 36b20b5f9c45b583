kinloop::mechanism! {
    /// Four mistakes in different items: all reported together.
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi + e == (x, 0) + l @ pis;
        point b = x;
        output w = log(x);
    }
}

fn main() {}
