// Angles computed, not named, as the length of `@`: twice the crank's angle, an angle offset by
// a number, and a scalar `let` of one. Each compiled into a link so many radians long, whose
// values changed with the unit of length. Where the angle of `@` is an angle too, or a constant,
// there is no swap to write, a length instead.
kinloop::mechanism! {
    pub struct Doubled {
        params r, l, s;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        let half = psi / 2;
        point a = (x, 0) + (2 * phi) @ psi;
        point b = (x, 0) + (phi + 0.0) @ s;
        point c = (x, 0) + half @ 0;
    }
}

fn main() {}
