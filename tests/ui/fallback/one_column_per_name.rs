// A name declared twice across inputs, unknowns, points and outputs is one error (with its
// first declaration); the named types emitted next to it have one column of that name.
kinloop::mechanism! {
    pub struct Cam {
        params h = 0.02;
        inputs phi, th;
        unknowns phi, s;
        eq lift: s == h * sin(phi) + th;
        point s = (s, 0);
        output th = 2 * s;
    }
}

fn main() {
    let _ = (Cam::COL.phi, Cam::COL.th, Cam::COL.s);
}
