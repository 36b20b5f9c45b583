kinloop::mechanism! {
    /// The `unknowns` item lacks its `;`.
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
