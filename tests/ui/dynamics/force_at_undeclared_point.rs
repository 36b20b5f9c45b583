kinloop::mechanism! {
    pub struct Engine {
        params r = 0.05, l = 0.2;
        input phi;
        unknowns beta = 0, x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        point s2 = r @ phi + 0.5 * l @ beta;
        force gas at piston = (100, 0);
    }
}

fn main() {}
