kinloop::mechanism! {
    // `x` is in a sine, but scaled (`x / l`): a length, not an angle a body turns with.
    pub struct Wobble {
        params a = 1.0, l = 2.0;
        input phi;
        unknowns x = 1.0;
        eq e: x == a * cos(phi) + 0.01 * sin(x / l);
        point pc = (x, 0);
        body k: mass 1.0, com pc, inertia 1.0, turns x;
        torque t on x = 1.0;
    }
}

fn main() {}
