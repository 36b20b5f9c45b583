kinloop::mechanism! {
    /// An equation written with `===`, as JavaScript compares: it said "found `=`" of the third
    /// `=`.
    pub struct SliderCrank {
        params r = 1, l = 3;
        input phi;
        unknowns psi, x, y;
        loop oab: r @ phi == (x, 0) + l @ psi;
        eq level: y === 1;
    }
}

fn main() {}
