// Functions of other libraries that are one or two edits from a built-in of another meaning:
// each says how it is written, where "did you mean" named that other function (`tanh` was
// `tan`, `sign` and `sgn` were `sin`, `cbrt` was `sqrt`, `cot` was `cos`, `sec` was `deg`,
// `exp2` was `exp`, `rad` was `max`), which would have compiled to other numbers.
kinloop::mechanism! {
    pub struct SliderCrank {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, 0) + l @ psi;
        output a = tanh(x);
        output b = sign(psi) * sgn(psi);
        output c = cbrt(x);
        output d = cot(psi) + sec(psi);
        output e = exp2(x);
        output f = rad(30);
    }
}

fn main() {}
