// An angle beside a length in one coordinate of a sum of vectors: `(x, 0) + (psi, 0)` is
// `(x + psi, 0)`, whose magnitude changes with the unit of length, though neither vector it adds
// mixes the two. Each compiled, where the same sum written in one tuple did not. The last two
// are one mistake each, told once: a tuple that mixes the two, added to; and a point, whose
// coordinate `psi` is told as an angle where a length belongs.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        output reach = norm((x, 0) + (psi, 0));
        output along = dot((x, r) - (0, psi), (cos(phi), sin(phi)));
        let v = (l, x) + (0, 2 * psi);
        output heading = angle(v);
        output both = norm((x, x) + (psi, psi));
        output once = norm((x, psi) + (0, x));
        point p = (x, 0) + (psi, 0);
    }
}

fn main() {}
