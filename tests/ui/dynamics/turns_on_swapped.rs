kinloop::mechanism! {
    pub struct Engine {
        params r = 0.05, l = 0.2, m = 2.0;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + beta @ l == (x, 0);
        body rod: mass m, com (x, 0), turns beta;
    }
}

fn main() {}
