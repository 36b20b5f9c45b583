// `psi @ (phi + e)`: the angle of `@` holds the crank's angle `phi` offset by `e`, of no known
// kind. The error said to swap the two, `(phi + e) @ psi`, a link whose length holds an angle;
// it says that swapping cannot help, what to write as the length, and what `phi + e` is if `e`
// is a length. `e`, a coordinate of the loop, is not refused as an angle by that term.
kinloop::mechanism! {
    pub struct Offset {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + l @ psi;
        point p = (x, 0) + psi @ (phi + e);
    }
}

fn main() {}
