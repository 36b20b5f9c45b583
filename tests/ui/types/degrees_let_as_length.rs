// A `let` of a value in degrees is an angle where it is written as a length, as the value itself
// is: `tilt @ l` compiled into a link 0.52 long turned by `l` radians, `(x, tilt)` into a point
// 0.52 above the guide, whatever the unit of length.
kinloop::mechanism! {
    pub struct Tilted {
        params r, l;
        input phi;
        unknowns psi, x;
        let tilt = 2 * deg(15);
        loop oab: r @ phi == (x, 0) + l @ psi;
        point a = (x, 0) + tilt @ l;
        point b = (x, tilt);
    }
}

fn main() {}
