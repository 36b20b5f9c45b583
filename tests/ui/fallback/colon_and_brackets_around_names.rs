// Names written after a `:` and inside brackets both: one error for the two, and the names keep
// their fields, so the code below adds no error of its own (it said "expected an input name"
// besides, and `SliderCrankInputs: From<{float}>` at the macro's call for `m.solve(0.5)`).
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input: (phi);
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {
    let m = SliderCrank { r: 1.0, l: 3.0 };
    let _ = m.solve(0.5).map(|s| s.q.psi + s.q.x);
}
