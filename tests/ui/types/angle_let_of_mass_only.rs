// A vector `let` with an angle for a coordinate that only a centre of mass takes, and one that
// only a force's point takes: the message said "a vector that a loop or point takes", naming
// neither use; it names the position that takes the vector.
kinloop::mechanism! {
    pub struct Weights {
        params r, l, m;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        let mark = (x, psi);
        body rod: mass m, com mark;
        let hit = (phi, 0);
        force push at hit = (1, 0);
    }
}

fn main() {}
