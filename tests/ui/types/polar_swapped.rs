kinloop::mechanism! {
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi, x;
        loop oab: r @ phi == (x, e) + psi @ l;
        point mid = r @ phi + 0.5 * l @ psi;
        // `psi` an angle by more than the two terms (else a tie: polar_bare_beside_expression_tie).
        output lean = sin(psi);
    }
}

fn main() {}
