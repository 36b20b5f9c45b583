kinloop::mechanism! {
    /// Under-determined: one loop for three unknowns. The error is reported once; the code in
    /// `main` that uses the mechanism's types adds no secondary error.
    pub struct FourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.5;
        input phi;
        unknowns beta, gamma, delta;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma + c @ delta;
        point coupler = a @ phi + b @ beta;
        output tr = gamma - beta;
    }
}

fn report(s: &FourBarState) -> f64 {
    s.q.beta + s.dq.gamma + s.out.coupler.x + s.d2out.tr
}

fn main() {
    let m = FourBar { a: 1.0, ..FourBar::default() };
    let q = FourBarUnknowns { beta: 0.1, gamma: 0.2, delta: 0.3 };
    let _ = (m.b + q.delta, FourBarInputs { phi: 0.0 }, report as fn(&FourBarState) -> f64);
}
