kinloop::mechanism! {
    pub struct CamSlider {
        params h = 0.02, beta = 1.5;
        input phi;
        unknowns s;
        let u = clamp(phi / beta, 1, 0);
        eq lift: s == h * u;
        output v = min(s, phi, h);
    }
}

fn main() {}
