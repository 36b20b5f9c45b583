// `pi` written as the Greek letter, as in a formula.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ (psi + π);
    }
}

fn main() {}
