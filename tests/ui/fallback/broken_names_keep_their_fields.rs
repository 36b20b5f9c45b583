kinloop::mechanism! {
    /// Mistakes inside name lists and in a point's and an output's value: every name that was
    /// written keeps its field, so `main` below adds no "no field" or conversion errors.
    pub struct SliderCrank {
        params r = 2 pi, l = 3.0, m: f64, k = 1;
        input self;
        unknowns psi = 3 deg, x;
        loop oab: r @ psi == (x, 0) + l @ psi;
        point b = (x, 0, 1);
        output w = x % 2;
    }
}

fn main() {
    let m = SliderCrank { l: 4.0, ..SliderCrank::default() };
    let _ = (m.r, m.m, m.k);
    let s = m.solve(0.5).unwrap();
    let _ = (s.q.psi, s.q.x, s.out.b.x, s.out.w);
}
