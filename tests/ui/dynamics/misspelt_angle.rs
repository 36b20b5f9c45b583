// A misspelt angle after `turns` or `on` gets the input or unknown meant.
kinloop::mechanism! {
    pub struct Engine {
        params r = 0.05, l = 0.2, m = 2.0, j = 0.01, c = 0.1;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        body rod: mass m, com (x, 0), inertia j, turns bet;
        torque load on ph = -c;
    }
}

fn main() {}
