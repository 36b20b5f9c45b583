// Loads written without their names: `at` and `on` are not taken for the names.
kinloop::mechanism! {
    pub struct Engine {
        params r = 0.05, l = 0.2, m = 0.5, c = 0.1;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        body piston: mass m, com (x, 0);
        force at (x, 0) = (-c, 0);
        torque on phi = -c;
    }
}

fn main() {}
