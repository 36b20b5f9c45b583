kinloop::mechanism! {
    pub struct Engine {
        params r = 0.05, l = 0.2;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        body rod: mass 2.0, com (x, 0) + 0.5 * l @ beta, inertia 0.01;
    }
}

fn main() {}
