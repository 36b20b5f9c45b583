// The two components of the vector `norm` takes, without their parentheses.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        output reach = norm(x, l);
    }
}

fn main() {}
