kinloop::mechanism! {
    /// Under-determined: the error is reported once; calls of the generated methods in `main`
    /// (solve, sweeps, guesses, analysis) add no secondary error.
    pub struct FourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.5;
        input phi;
        unknowns beta, gamma, delta;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma + c @ delta;
        point coupler = a @ phi + b @ beta;
    }
}

fn main() -> Result<(), kinloop::Error> {
    let m = FourBar::default();
    let s = m.solve(0.3)?;
    let g = m.guess(0.0);
    let _ = m.sweep(0.0, 1.0, 10, &g)?.run();
    let sampled = m.sampled(0.0, 1.0, 10, &g)?;
    let _ = sampled.range(FourBar::COL.beta);
    let _ = (s.q.beta, s.out.coupler.x, FourBar::UNKNOWNS.len());
    Ok(())
}
