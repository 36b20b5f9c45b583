kinloop::mechanism! {
    /// Declared without `#[kinloop(sensitivities)]`: `sensitivities` is not generated, and
    /// calling it says which attribute to add.
    pub struct FourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.5;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

fn main() {
    let m = FourBar::default();
    let q = m.solve(0.3).unwrap().q;
    let _ = m.sensitivities(0.3, &q);
    let _ = m.sensitivities_at(0.3, &q);
}
