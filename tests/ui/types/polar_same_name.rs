// `beta @ beta`: one name as both the length and the angle. Swapping the two writes the same
// term, so the advice is a length where the length belongs, not a swap.
kinloop::mechanism! {
    pub struct FourBar {
        params a, c, d;
        input phi;
        unknowns beta, gamma;
        loop abcd: a @ phi + beta @ beta == (d, 0) + c @ gamma;
    }
}

fn main() {}
