// Where the angle of `@` is an angle too, swapping the two cannot help: a rod's angle turned by
// the crank's, twice an angle, and a value in degrees, each as the length of a term turned by
// `phi`. Each was told to write the swap, a link `phi` radians long; each is told to write a
// length instead.
kinloop::mechanism! {
    pub struct Both {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + l @ psi;
        point a = (x, 0) + psi @ phi;
        point b = (x, 0) + (2 * psi) @ phi;
        point c = (x, 0) + deg(3) @ phi;
    }
}

fn main() {}
