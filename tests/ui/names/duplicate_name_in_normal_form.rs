// One name written two ways: `lé` with the precomposed letter (U+00E9) as the parameter,
// and with `e` and a combining acute accent (U+0065 U+0301) as the unknown. The compiler reads
// identifiers in Unicode Normalization Form C, so both are the same name, declared twice.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, lé;
        input phi;
        unknowns psi, lé;
        loop oab: r @ phi == (lé, 0) + lé @ psi;
    }
}

fn main() {}
