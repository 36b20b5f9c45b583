// Values defined from themselves: a `let` written as an update, as in a loop of a program, and
// two outputs defined from each other. Neither is an ordering that moving a line would mend.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        let gap = x - r;
        let gap = gap + l;
        output lead = trail + x;
        output trail = lead - x;
        output twice = 2 * twice;
    }
}

fn main() {}
