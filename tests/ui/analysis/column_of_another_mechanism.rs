
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oabo: r @ phi == (x, 0) + l @ psi;
    }
}

kinloop::mechanism! {
    pub struct FourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

fn main() -> Result<(), kinloop::Error> {
    let m = SliderCrank::default();
    let turn = m.sampled(0.0, 6.0, 61, &m.guess(0.0))?;
    // Column handles carry their mechanism: the four-bar's `beta` is no column of the slider-crank.
    let _swing = turn.range(FourBar::COL.beta)?;
    Ok(())
}
