// A Rust keyword where a parameter's name belongs: the macro's error alone, the struct literal
// below adds none (it missed the field `__kinloop_keyword_type` of the stand-in kept for it).
kinloop::mechanism! {
    pub struct SliderCrank {
        params r, type;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + 3 @ psi;
    }
}

fn main() {
    let m = SliderCrank { r: 1.0 };
    let _ = m.solve(0.5).map(|s| s.q.psi + s.q.x);
}
