// A name declared in Greek, as a paper writes it (`φ`), and used spelt out (`phi`): the
// suggestion is the Greek name, not the Latin one an edit away (it was "did you mean `psi`?").
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input φ;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {}
