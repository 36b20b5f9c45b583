// An angle beside a length: a rack's travel set equal to the pinion's angle by an `eq`, and a
// `let` that adds a slider's position and a rod's angle. Each compiled into values that
// changed with the unit of length (the travel `phi` millimetres or `phi` metres).
kinloop::mechanism! {
    pub struct Rack {
        params r, l;
        input phi;
        unknowns psi, x, s;
        loop oab: r @ phi == (x, s) + l @ psi;
        eq rack: s == phi;
        let lead = x + psi;
        output ahead = lead;
    }
}

fn main() {}
