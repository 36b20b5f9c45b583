// The option in the singular, three edits from the word meant: it is named, as a misspelt
// option one or two edits away is.
kinloop::mechanism! {
    #[kinloop(sensitivity)]
    pub struct FourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.5;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

fn main() {}
