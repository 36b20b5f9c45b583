// kinloop under another name, as a crate that renames the dependency in its `Cargo.toml` has it:
// `::kinloop` names this crate (which has none of kinloop's items), kinloop is linked as `kl`.
// The items emitted beside the errors reach the runtime as the expansion does, through the
// wrapper's `$crate`: the code in `main` that uses them adds no secondary error.
extern crate self as kinloop;
extern crate kinloop as kl;

kl::mechanism! {
    /// An unknown name: the error is reported once, at the name.
    pub struct FourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.5;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gama;
        point coupler = a @ phi + b @ beta;
    }
}

fn report(s: &FourBarState) -> f64 {
    s.q.beta + s.dq.gamma + s.out.coupler.x
}

fn main() {
    let m = FourBar { a: 1.0, ..FourBar::default() };
    let q = FourBarUnknowns { beta: 0.1, gamma: 0.2 };
    let _ = (m.b + q.gamma, FourBarInputs { phi: 0.0 }, report as fn(&FourBarState) -> f64);
}
