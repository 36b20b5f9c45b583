kinloop::mechanism! {
    pub struct Engine {
        params r = 0.05, l = 0.2;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        body piston: mass 0.5, com (x, 0), inertia 0.01, turns x;
        body crank: mass 1.0, com r @ phi, turns r;
    }
}

fn main() {}
