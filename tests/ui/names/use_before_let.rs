kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: crank == (x, 0) + l @ psi;
        let crank = r @ phi;
    }
}

fn main() {}
