// A vector `let` with an angle for a coordinate, used by a point and by a centre of mass: one
// mistake, reported once at the coordinate (the centre of mass was refused again, without the
// coordinate to mend).
kinloop::mechanism! {
    pub struct Rod {
        params r, l, m;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        let mark = (x, psi);
        point tip = mark;
        body rod: mass m, com mark;
    }
}

fn main() {}
