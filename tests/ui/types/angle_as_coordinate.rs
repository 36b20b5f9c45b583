// Angles as coordinates of the vectors of a loop, which adds lengths: the crank's angle as the
// height of a slider's guide, and a guide's offset written in degrees. Each compiled into a
// mechanism whose results changed with the unit of length.
kinloop::mechanism! {
    pub struct TwinSliders {
        params r, l, e = deg(5);
        input phi;
        unknowns psi, x, psi2, x2;
        loop oab: r @ phi == (x, phi) + l @ psi;
        loop oac: r @ phi == (x2, e) + l @ psi2;
    }
}

fn main() {}
