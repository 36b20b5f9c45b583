kinloop::mechanism! {
    pub struct Engine {
        params r = 0.05, l = 0.2;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        body piston: mass 2 * x, com (x, 0);
        gravity 9.81;
    }
}

fn main() {}
