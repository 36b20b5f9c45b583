// Two options without the `,` between them, and an option in quotes.
kinloop::mechanism! {
    #[kinloop(dense newton)]
    #[kinloop("sensitivities")]
    pub struct FourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.5;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

fn main() {}
