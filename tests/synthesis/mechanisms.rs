//! The mechanisms synthesised, declared with sensitivities, and their positions in closed form
//! (plain trigonometry, independent of kinloop) to sample targets from.

kinloop::mechanism! {
    /// Four-bar with a coupler point: crank `a` at the origin, coupler `b`, rocker `c` at
    /// (d, 0); the point `p` at distance `e` from the crank pin, `alpha` off the coupler line; `theta` the angle of the line from
    /// the crank pin to `p` (the coupler's angle in a motion task).
    #[kinloop(sensitivities)]
    pub struct CouplerFourBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.0, e = 1.5, alpha = 0.6;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point p = a @ phi + e @ (beta + alpha);
        output theta = beta + alpha;
    }
}

kinloop::mechanism! {
    /// Offset slider-crank: crank `r` at the origin, rod `l`, slider at (x, e) on the -x side.
    #[kinloop(sensitivities)]
    pub struct Slider {
        params r = 1.0, l = 3.0, e = 0.5;
        input phi;
        unknowns psi = 0, x = -l;
        loop oabo: r @ phi == (x, e) + l @ psi;
    }
}

/// The four-bar's truth: `[a, b, c, d, e, alpha]`.
pub const FOUR_BAR: [f64; 6] = [1.0, 3.2, 2.4, 3.1, 1.7, 0.45];

/// The coupler point of a four-bar `[a, b, c, d, e, alpha]` at crank angle `phi`, with the
/// coupler joint C on the left of the line from the crank pin A to the rocker pivot D (the
/// assembly mode of the declared guess): circle intersection in closed form.
pub fn coupler_point(p: [f64; 6], phi: f64) -> [f64; 2] {
    four_bar_pose(p, phi, 1.0).0
}

/// The coupler point and the angles `[beta, gamma]` of a four-bar at crank angle `phi`, with C
/// on side `side` of the line from A to D (+1 left, -1 right).
pub fn four_bar_pose(p: [f64; 6], phi: f64, side: f64) -> ([f64; 2], [f64; 2]) {
    let [a, b, c, d, e, alpha] = p;
    let (ax, ay) = (a * phi.cos(), a * phi.sin());
    let (cx, cy) = crate::support::circle_point(ax, ay, b, d, 0.0, c, side);
    let beta = (cy - ay).atan2(cx - ax);
    let gamma = cy.atan2(cx - d);
    ([ax + e * (beta + alpha).cos(), ay + e * (beta + alpha).sin()], [beta, gamma])
}

/// The slider's truth: `[r, l, e]`.
pub const SLIDER: [f64; 3] = [1.1, 3.4, 0.35];

/// The slider's position of a slider-crank `[r, l, e]` at crank angle `phi` (rod pointing
/// back to the slider on the -x side).
pub fn slider_x(p: [f64; 3], phi: f64) -> f64 {
    let [r, l, e] = p;
    r * phi.cos() - (l * l - (r * phi.sin() - e).powi(2)).sqrt()
}

kinloop::mechanism! {
    /// Stephenson six-bar: the four-bar above, and a dyad from its coupler point P (link `f`,
    /// angle `delta`) to a ground pivot G = (gx, gy) (link `g`, angle `eps`); the traced point
    /// `r` lies on the dyad's first link at distance `h` from P.
    #[kinloop(sensitivities)]
    pub struct Stephenson {
        params a = 1.0, b = 3.2, c = 2.4, d = 3.1, e = 1.7, alpha = 0.45, f = 2.2, g = 2.6, gx = 0.8,
               gy = 4.6, h = 3.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, delta = 0.3, eps = -1.0;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop peg: a @ phi + e @ (beta + alpha) + f @ delta == (gx, gy) + g @ eps;
        point r = a @ phi + e @ (beta + alpha) + h @ delta;
    }
}

/// The six-bar's truth, in declaration order.
pub const STEPHENSON: [f64; 11] = [1.0, 3.2, 2.4, 3.1, 1.7, 0.45, 2.2, 2.6, 0.8, 4.6, 3.0];

/// The six-bar's traced point at crank angle `phi`: the four-bar's coupler point P (C on the
/// left of AD), the dyad's joint E on the right of the line from P to G, `r` on PE.
pub fn stephenson_point(p: [f64; 11], phi: f64) -> [f64; 2] {
    let [a, b, c, d, e, alpha, f, g, gx, gy, h] = p;
    let [px, py] = coupler_point([a, b, c, d, e, alpha], phi);
    let (ex, ey) = crate::support::circle_point(px, py, f, gx, gy, g, -1.0);
    let delta = (ey - py).atan2(ex - px);
    [px + h * delta.cos(), py + h * delta.sin()]
}

kinloop::mechanism! {
    /// Four-bar function generator in Freudenstein's frame: input `a` at the origin at angle
    /// `phi`, coupler `b`, output `c` pivoted at (d, 0) at angle `psi`.
    #[kinloop(sensitivities)]
    pub struct FunctionFourBar {
        params a = 3.0, b = 2.0, c = 4.0, d = 1.0;
        input phi;
        unknowns beta = 0.3, psi = 1.6;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ psi;
    }
}

kinloop::mechanism! {
    /// Four-bar anywhere in the plane, for motion generation: input pivot A = (ax, ay), ground
    /// `g` at angle `th`, input `a` at `phi` from the ground line, coupler `b` (angle `beta`),
    /// output `c` (angle `gamma`); the body's point `p` at `e`, `alpha` off the coupler line,
    /// its angle `theta` at `tau` from the coupler line.
    #[kinloop(sensitivities)]
    pub struct PlacedFourBar {
        params ax = 0.0, ay = 0.0, g = 4.0, th = 0.0, a = 1.5, b = 4.0, c = 3.0, e = 2.5, alpha = 0.6, tau = 0.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ (phi + th) + b @ beta == g @ th + c @ gamma;
        point p = (ax, ay) + a @ (phi + th) + e @ (beta + alpha);
        output theta = beta + tau;
    }
}
