// Doc comments written inside items, where they document nothing: each is named as a doc
// comment (not as the `#` the parser reads it as) with where to write it, and one that starts
// the next item after an item without its `;` leaves the missing `;` the error.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0 /// the crank
            , l = 3.0;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi   /// the crank
            == (x, 0)       /// the slider
            + l @ psi;
        let /// the crank's end
            b = r @ phi;
        point c = (x, 0)
        /// The gap between the slider and the crank's length.
        output gap = x - r;
    }
}

fn main() {}
