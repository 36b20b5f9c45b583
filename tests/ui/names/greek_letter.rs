// A name written with a Greek letter, as a paper writes the angle: told the name spelling it out.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ φ == (x, 0) + l @ psi;
    }
}

fn main() {}
