// `_` where a name belongs: a placeholder, not a name, and `r#_` is no raw identifier.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0, _;
        input phi;
        unknowns psi = 0.5, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
