// An angle beside a length in the law of a force or a torque: a torque that adds a slider's
// position and a rod's angle, a force whose coordinate subtracts the one from the other, and a
// force whose vector puts the one beside the other. Each compiled into loads whose values
// changed with the unit of length, where the same sums in an `output` did not. A law in terms
// of parameters of no known kind (a stiffness `k`, a damping `c`) is judged by no unit.
kinloop::mechanism! {
    pub struct Engine {
        params r = 0.05, l = 0.2, m = 0.5, k = 10.0, c = 0.1;
        input phi;
        unknowns psi = 0, x = 0.25;
        loop rod: r @ phi + l @ psi == (x, 0);
        body piston: mass m, com (x, 0);
        torque spring on psi = x + psi;
        force push at (x, 0) = (x - 2 * psi, 0);
        force pull at (x, 0) = (x, psi);
        torque fine on psi = -k * x - c * psi;
    }
}

fn main() {}
