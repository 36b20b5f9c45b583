kinloop::mechanism! {
    #[doc = 1]
    pub struct SliderCrank {
        params #[doc = norm "crank"] r, l;
        input phi;
        unknowns psi, x;
        #[doc(hidden)]
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
