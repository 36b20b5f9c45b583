// Angles computed, not named, as coordinates of positions: an angle offset by a number, a
// multiple of one, a scalar `let` of one, the dot product of an angle's vector with a direction,
// an angle scaling a direction, and twice an angle as a centre of mass's coordinate. Each
// compiled into positions whose values changed with the unit of length (the last was told to
// declare the point, which would not have mended it).
kinloop::mechanism! {
    pub struct Offsets {
        params r, l, m;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, phi + 0.0) + l @ psi;
        let half = psi / 2;
        point tip = (2.0 * psi, half);
        point peg = (x, 0) + (dot((psi, 0), (1, 0)), 0);
        point top = (x, 0) + psi * (0, 1);
        body slider: mass m, com (x, 2 * psi);
    }
}

fn main() {}
