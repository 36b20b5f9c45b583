// The last item ended with `,` as a Rust struct's last field is: one error at the `,`, saying to
// write `;`, not a name expected after it and a `;` missing as two mistakes.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input phi;
        loop oab: r @ phi == (x, 0) + l @ psi;
        unknowns psi, x,
    }
}

fn main() {
    let _ = SliderCrank::default().solve(0.5).map(|s| s.q.psi + s.q.x);
}
