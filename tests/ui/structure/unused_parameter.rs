kinloop::mechanism! {
    /// `mass` is unused: a warning, not an error (`_speed` is unused on purpose).
    pub struct SliderCrank {
        params r, l, mass, _speed;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oab: r @ phi == (x, 0) + l @ psi;
    }
}

fn main() {
    let _ = SliderCrank { r: 1.0, l: 3.0, mass: 2.0, _speed: 0.0 }.solve(0.3);
    compile_error!("this case checks the warning above; the mechanism itself compiles");
}
