kinloop::mechanism! {
    /// `Self`, a Rust keyword, as the mechanism's name: it said "expected the mechanism's name"
    /// without saying why `Self` is none.
    pub struct Self {
        params r = 1, l = 3;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
