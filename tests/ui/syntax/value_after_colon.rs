// Values given after `:`, as YAML writes them: `=` gives a value.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r: 1.0, l = 3.0;
        input phi;
        unknowns psi: -0.5, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
