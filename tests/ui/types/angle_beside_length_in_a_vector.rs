// A vector of an angle and a length changes with the unit of length, as their sum would: its
// magnitude, its products, its direction.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        output reach = norm((x, psi));
        output along = dot((x, psi), (cos(phi), sin(phi)));
        let v = (x, 0) + (0, psi);
        output heading = angle(v);
    }
}

fn main() {}
