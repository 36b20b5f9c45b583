//! A cosine whose sine appears only through differentiation (created after nodes that use the
//! cosine): the generated code computes both with one `sin_cos` where the first of them is
//! needed, so every use stays after its definition.

use crate::support::tol;

kinloop::mechanism! {
    /// `a cos(q) + b q = x`: the residual uses `cos(q)`, the Jacobian `-a sin(q) + b`.
    pub struct CosFirst {
        params a, b;
        input x;
        unknowns q = 0.1;
        eq e: a * cos(q) + b * q == x;
    }
}

#[test]
fn cosine_before_its_sine_compiles_and_solves() {
    let m = CosFirst { a: 0.5, b: 2.0 };
    let x = 1.3;
    let k = m.kinematics(x, &m.guess(x)).unwrap();
    let q = k.q.q;
    assert_close!(m.a * q.cos() + m.b * q, x, <= tol::SOLVE);
    // dq/dx = 1 / (b - a sin q); d2q/dx2 = a cos(q) q'^2 / (b - a sin q).
    let d = m.b - m.a * q.sin();
    assert_close!(k.dq.q, 1.0 / d, <= tol::SOLVE);
    assert_close!(k.d2q.q, m.a * q.cos() / d.powi(3), <= tol::SOLVE);
}
