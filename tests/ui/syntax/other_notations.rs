// Notations of formulas and other languages: a number without its leading `0`, and `gravity`
// given its vector with `=`. Each is told what to write.
kinloop::mechanism! {
    pub struct Engine {
        params r, l, m, g;
        input phi;
        unknowns psi = .5, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        body piston: mass m, com (x, 0);
        gravity = (0, -g);
    }
}

fn main() {}
