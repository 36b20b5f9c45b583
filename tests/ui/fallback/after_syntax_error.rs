kinloop::mechanism! {
    /// A syntax error in one item: the parameter struct and the named types are still emitted,
    /// so `main` below adds no "cannot find type" or "no field" errors.
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi = (x, 0) + l @ psi;
        point b = r @ phi;
    }
}

fn main() {
    let m = SliderCrank { l: 4.0, ..SliderCrank::default() };
    let q: SliderCrankUnknowns = SliderCrankUnknowns { psi: 0.0, x: m.r + m.l };
    let out = SliderCrankOutputs { b: kinloop::Vec2 { x: q.x, y: 0.0 } };
    let _ = (out.b.x, SliderCrankInputs::<f64> { phi: 0.0 });
}
