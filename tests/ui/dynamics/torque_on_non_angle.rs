kinloop::mechanism! {
    pub struct Engine {
        params r = 0.05, l = 0.2, c = 0.1;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        torque friction on x = -c;
        torque load on c = -c;
    }
}

fn main() {}
