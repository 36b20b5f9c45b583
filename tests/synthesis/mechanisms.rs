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
