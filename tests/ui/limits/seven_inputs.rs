kinloop::mechanism! {
    pub struct Seven {
        params l = 1;
        input a, b, c, d, e, f, g;
        unknowns x = 1;
        eq sum: x == l + a + b + c + d + e + f + g;
    }
}

fn main() {}
