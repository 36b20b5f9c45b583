kinloop::mechanism! {
    pub struct Cam {
        /*! A cam with a flat follower. */
        params h = 0.02;
        input phi;
        unknowns s;
        eq lift: s == h * sin(phi);
    }
}

fn main() {}
