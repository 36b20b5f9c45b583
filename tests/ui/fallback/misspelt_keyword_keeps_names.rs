// Items whose keyword is misspelt: each is named with the keyword meant, and the names they
// declare keep their fields, so the code below that uses them adds no error of its own (it had
// `no field named r`, `no field gap on MOutputs`, and `MInputs: From<{float}>` at the macro call).
kinloop::mechanism! {
    pub struct SliderCrank {
        parms r = 1.0, l = 3.0;
        imput phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        ouput gap = x - r;
    }
}

fn main() {
    let m = SliderCrank { r: 1.0, l: 3.0 };
    if let Ok(s) = m.solve(0.5) {
        let _ = s.out.gap + s.q.psi;
    }
}
