// Item keywords misspelt, or written as another language would: each is named with the keyword
// meant, and the items after it are still read.
kinloop::mechanism! {
    pub struct SliderCrank {
        parameters r, l;
        imput phi;
        unknowns psi, x;
        lop oab: r @ phi == (x, 0) + l @ psi;
        Output gap = x - r;
    }
}

fn main() {}
