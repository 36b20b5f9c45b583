kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, gamma;
        input phi;
        unknowns psi, x;
        // `@` binds tighter than `+`: the angle needs parentheses.
        loop oab: r @ phi + gamma == (x, 0) + l @ psi;
    }
}

fn main() {}
