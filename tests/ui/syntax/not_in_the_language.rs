kinloop::mechanism! {
    /// Rust that kinloop does not speak, each with what to write instead.
    pub struct Crank {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi == (0, 0);
        output turns = phi % 2;
        output ahead = x > 2;
        output half = std::f64::consts::PI / 2;
        output first = x[0];
        output offset = phi + 30 deg;
        output circle = 2 pi * r;
    }
}

fn main() {}
