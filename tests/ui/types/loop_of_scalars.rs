kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r * cos(phi) == x + l * cos(psi);
        eq y: r * sin(phi) == l * sin(psi);
    }
}

fn main() {}
