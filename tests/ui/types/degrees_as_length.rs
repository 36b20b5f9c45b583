// Angles in degrees where a polar term takes its length (`length @ angle`): as the value of a
// name, scaled by a number, or written there directly. Each compiled before into a link a
// fraction of a unit long.
kinloop::mechanism! {
    pub struct OffsetGuides {
        params r, l, d, e, tilt = 2 * deg(15);
        input phi;
        unknowns th = deg(20) * 2, s = d, psi, x;
        loop guide: r @ phi == (d, 0) + th @ s;
        loop rod: r @ phi + tilt @ e == (x, 0) + l @ psi;
        point pin = (x, 0) + deg(30) @ e;
        point tip = (x, 0) + 2 * deg(15) @ 0;
    }
}

fn main() {}
