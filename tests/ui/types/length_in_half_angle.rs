// A slider's travel scaled into a sine by a number (`sin(x / 2)`, a pinion of radius 2 written
// as a number) is a length still: its place in the loop and as the length of `@` say so. It was
// taken for an angle, and the loop's `(x, 0)` and `x @ psi` refused with a swap to write; only
// the rod's angle written as a coordinate is.
kinloop::mechanism! {
    pub struct Rack {
        params r, l;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        point a = x @ psi;
        point b = (x, psi);
        output turn = sin(x / 2);
    }
}

fn main() {}
