kinloop::mechanism! {
    /// A misspelled name: the error is reported once; calls of the requested sensitivity API in
    /// `main` (named sensitivities, synthesis-style generic code) add no secondary error.
    #[kinloop(sensitivities)]
    pub struct FourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.5;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gama;
        point coupler = a @ phi + b @ beta;
    }
}

fn flat<M: kinloop::Sensitivities<2, 1, 2, 4>>(m: &M) -> [f64; 4] {
    m.params_flat()
}

fn main() -> Result<(), kinloop::Error> {
    let m = FourBar::default();
    let (s, sens) = m.sensitivities(0.3, &m.guess(0.3))?;
    let _ = (s.q.beta, sens.dq.beta.a, sens.out.coupler.x.b, sens.q.gamma.d);
    let (_, at) = m.sensitivities_at(0.3, &s.q)?;
    let _ = (at.q.beta.c, flat(&m));
    Ok(())
}
