kinloop::mechanism! {
    /// No masses, inertias or loads are declared: `mass_model` says what to add.
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {
    let m = SliderCrank { r: 1.0, l: 3.0 };
    let _ = m.mass_model();
}
