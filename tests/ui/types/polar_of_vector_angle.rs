// A vector as the angle of `@`: one error, not a second one for the angle inside the vector.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        point p = r @ (phi, 1);
    }
}

fn main() {}
