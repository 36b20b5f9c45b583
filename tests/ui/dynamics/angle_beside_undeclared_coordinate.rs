// An angle beside a coordinate that a declared point would give: the angle is the mistake, and
// declaring the point would not mend it. Each position got both errors, the second asking to
// declare a point of an angle; it gets the angle's alone.
kinloop::mechanism! {
    pub struct Rod {
        params r, l, m;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        body rod: mass m, com (psi, x * l);
        force push at (phi, x / 2) = (1, 0);
    }
}

fn main() {}
