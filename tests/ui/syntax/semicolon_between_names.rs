// A `;` for the `,` between the names of a list: the name after it joins the list with a `,`,
// and keeps its field, so `main` below adds no "no field" error.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi = 0.5; x = 4.0;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {
    let s = SliderCrank::default().solve(0.5).unwrap();
    let _ = (s.q.psi, s.q.x);
}
