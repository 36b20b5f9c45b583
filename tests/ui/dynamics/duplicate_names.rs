kinloop::mechanism! {
    pub struct Engine {
        params r = 0.05, l = 0.2, m = 2.0, p = 300.0;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        point rod = r @ phi + 0.5 * l @ beta;
        body rod: mass m, com rod, turns beta;
        body rod: mass m, com (x, 0);
        force gas at (x, 0) = (p, 0);
        torque gas on phi = -p * r;
        force lift at rod = (0, p);
    }
}

fn main() {}
