kinloop::mechanism! {
    /// Names of a list, and the clauses of a body, without their `,`.
    pub struct Engine {
        params r = 0.05 l = 0.2, m;
        inputs phi;
        unknowns beta x = 0.25;
        loop abc: r @ phi + l @ beta == (x, 0);
        body piston: mass m com (x, 0);
    }
}

fn main() {}
