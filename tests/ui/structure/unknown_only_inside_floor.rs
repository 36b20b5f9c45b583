kinloop::mechanism! {
    pub struct Indexer {
        params h = 0.5;
        input phi;
        unknowns n = 1, s;
        eq turns: floor(n) == floor(phi / (2 * pi));
        eq lift: s == h * sin(phi) + n;
    }
}

fn main() {}
