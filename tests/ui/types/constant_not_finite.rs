kinloop::mechanism! {
    pub struct Cam {
        params h = 0.02, r = exp(1000);
        input phi;
        unknowns s = asin(2);
        eq lift: s == h * sin(phi) + ln(0);
        output w = clamp(s, 0, 10 ^ 400);
        output v = s + 1e308 * 10;
    }
}

fn main() {}
