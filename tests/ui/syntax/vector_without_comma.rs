// A vector without the `,` between its components.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi = 0.5, x = 4.0;
        loop oab: r @ phi == (x 0) + l @ psi;
    }
}

fn main() {}
