// A body's clauses ended with `,` before the next item: the `,` is said to stand for the `;`,
// not read as the start of a clause the body does not have (`gravity`).
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0, m = 0.5;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        body piston: mass m, com (x, 0),
        gravity (0, -9.81);
    }
}

fn main() {}
