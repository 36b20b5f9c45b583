
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oabo: r @ phi == (x, 0) + l @ psi;
        point b = r @ phi;
    }
}

fn main() -> Result<(), kinloop::Error> {
    let m = SliderCrank::default();
    let turn = m.sampled(0.0, 6.0, 61, &m.guess(0.0))?;
    // A column name is a field of `SliderCrank::COL`: a typo is a compile error, not a run-time one.
    let _stroke = turn.range(SliderCrank::COL.xc)?;
    let _path = turn.range(SliderCrank::COL.b.z)?;
    Ok(())
}
