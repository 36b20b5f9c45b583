// Attributes before an item or a name: each is said to be removed, and the names after them
// keep their fields, so the code below that uses them adds no error of its own.
kinloop::mechanism! {
    pub struct SliderCrank {
        #[allow(unused)]
        params r = 1.0, l = 3.0;
        params #[serde(skip)] e = 0.1;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + l @ psi;
    }
}

fn main() {
    let m = SliderCrank { r: 1.0, l: 3.0, e: 0.1 };
    let _ = m.r + m.l + m.e;
}
