kinloop::mechanism! {
    pub struct CamSlider {
        params h = 0.02, beta = 1.5;
        input phi;
        unknowns s;
        let t = wrap(phi, -2 * pi);
        let u = wrap(phi, 0);
        eq lift: s == h * (t + u + floor(phi, 2));
        output v = fmod(s, 1);
    }
}

fn main() {}
