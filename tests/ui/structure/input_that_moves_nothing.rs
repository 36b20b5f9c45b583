kinloop::mechanism! {
    /// Inputs that are named, but on which no equation or output depends.
    pub struct SliderCrank {
        params r, l;
        inputs phi, t, s;
        let drift = 2 * t;
        unknowns psi, x = l + s;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

kinloop::mechanism! {
    pub struct Cancelled {
        params h;
        input phi;
        unknowns s;
        eq lift: s == h + phi - phi;
    }
}

fn main() {}
