// The magnitude of a vector of angles where a length belongs: as a coordinate of a point, as
// the length of `@`, and as a coordinate of a centre of mass. Each compiled into positions
// whose values changed with the unit of length.
kinloop::mechanism! {
    pub struct Magnitudes {
        params r, l, m;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        point a = (x, norm((phi, psi)));
        point b = (x, 0) + hypot(psi, 0.1) @ phi;
        body slider: mass m, com (x, norm((psi, 0)));
    }
}

fn main() {}
