// Angles as coordinates of positions other than a loop's vectors: a point, a vector `let` that
// a point uses, the point a force acts at and a centre of mass, as a name that turns a link, a
// name whose value is in degrees, or degrees written there. Each compiled into outputs (and a
// mass model) that changed with the unit of length.
kinloop::mechanism! {
    pub struct Marked {
        params r, l, m, e = deg(5);
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        point tip = (x, psi);
        point peg = (x, 0) + (e, 0);
        let lift = (0, deg(10));
        point top = tip + lift;
        body slider: mass m, com (x, e);
        force push at (phi, 0) = (1, 0);
    }
}

fn main() {}
