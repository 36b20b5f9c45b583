// `deg` written as a unit after or before its number: it is a function, `deg(30)`.
kinloop::mechanism! {
    pub struct Tilted {
        params r = 1.0, l = 3.0, tilt = 30deg;
        input phi;
        unknowns psi = deg 150, x = 4.0;
        loop c: r @ phi == (x, 0) + l @ psi;
        output w = psi - 1.5rad;
    }
}

fn main() {}
