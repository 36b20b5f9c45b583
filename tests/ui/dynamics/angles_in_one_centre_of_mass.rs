// Two wrong coordinates in one centre of mass or force's point: an angle unknown beside twice an
// angle, beside an angle input, and an angle unknown that a point is refused for too. The
// dynamics' message about the unknown was lost to the other coordinate's (or the point's)
// refusal; each wrong coordinate gets its one error.
kinloop::mechanism! {
    pub struct Pair {
        params r, l, m;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        point tip = (x, psi);
        body rod: mass m, com (psi, 2 * phi);
        body pin: mass m, com (x, psi);
        force push at (psi, phi) = (1, 0);
    }
}

fn main() {}
