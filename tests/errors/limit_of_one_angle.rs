//! Closed forms of one angle (`a cos q + b sin q = c`) at a limit position, in metres,
//! millimetres and micrometres and at sizes from `1e-100` to `1e100`: the verdict (the limit
//! position, or "cannot be assembled") is the same in every unit and at every size, and is
//! Newton's: where the links laid at the limit close the loop within the residual tolerance of
//! the magnitude of the equation's terms (the sum of the loop's lengths), the limit position;
//! where they miss by more, no assembly, with that miss over that magnitude as residual.
//!
//! Two designs, each written in decimal so that it closes exactly at its limit:
//! * an offset slider-crank (crank `r` about `(0, e)`, rod `l` to the slider `(x, 0)`, its rod's
//!   angle from the loop's Y projection `l sin psi = e + r sin phi`, an angle equation with a
//!   folded coefficient) at `phi = pi/2`, where `r + e = l`: the rod stands vertical;
//! * a slider-crank on an inclined slide (crank `r` about `(0, h)`, the slide through the origin
//!   along the unit vector `(u, v) = (0.6, 0.8)`, an angle and a slider) at `phi = 0`, where the
//!   crank pin `(r, h)` lies `u h - v r = l` from the slide: the rod stands square to it.
//!
//! The reference is that construction: the miss `delta` of the links at the limit, and the
//! loop's closure computed here from the returned angles. With a short rod beside a long crank,
//! the equation's right side `c` is a difference of terms much larger than itself, and its
//! rounding depends on the unit: the verdict was taken relative to `|c|` alone, so a design
//! closing exactly in decimal was "cannot be assembled" in some units and a position in others.

use kinloop::{Error, Mechanism, NewtonConfig};
use std::f64::consts::FRAC_PI_2;

kinloop::mechanism! {
    /// An offset slider-crank: crank `r` about `O = (0, e)`, rod `l` from the crank pin to the
    /// slider `C = (x, 0)`.
    pub struct OffsetSliderCrank {
        params r, l, e;
        input phi;
        unknowns psi = 1.5, x = 0;
        loop ocb: (0, e) + r @ phi == (x, 0) + l @ psi;
    }
}

kinloop::mechanism! {
    /// A slider-crank on an inclined slide: crank `r` about `(0, h)`, rod `l` from the crank pin
    /// to the slider `x (u, v)` on the slide through the origin along the unit vector `(u, v)`.
    pub struct InclinedSliderCrank {
        params r, l, h, u, v;
        input phi;
        unknowns psi = 1.0, x = 0;
        loop ocb: (0, h) + r @ phi == x * (u, v) + l @ psi;
    }
}

/// The two kinds of design, each with its construction.
#[derive(Clone, Copy, Debug)]
enum Design {
    /// The offset slider-crank at `phi = pi/2`: crank `r`, rod `l`, offset `e`.
    Offset { r: f64, l: f64, e: f64 },
    /// The inclined slider-crank at `phi = 0`: crank `r` about `(0, h)`, rod `l`, slide along
    /// `(0.6, 0.8)`.
    Inclined { r: f64, l: f64, h: f64 },
}

/// The inclined slide's direction, a unit vector in decimal (`0.36 + 0.64 = 1`).
const SLIDE: (f64, f64) = (0.6, 0.8);

impl Design {
    /// The design at `k` times its size.
    fn scaled(self, k: f64) -> Design {
        match self {
            Design::Offset { r, l, e } => Design::Offset { r: r * k, l: l * k, e: e * k },
            Design::Inclined { r, l, h } => Design::Inclined { r: r * k, l: l * k, h: h * k },
        }
    }

    /// The design with its rod shortened by `by`.
    fn shorter(self, by: f64) -> Design {
        match self {
            Design::Offset { r, l, e } => Design::Offset { r, l: l - by, e },
            Design::Inclined { r, l, h } => Design::Inclined { r, l: l - by, h },
        }
    }

    /// The input of the limit position.
    fn input(self) -> f64 {
        match self {
            Design::Offset { .. } => FRAC_PI_2,
            Design::Inclined { .. } => 0.0,
        }
    }

    /// The rod's angle at the limit position: vertical (`l sin psi = e + r`), or square to the
    /// slide on the crank pin's side (along `(-v, u)`).
    fn limit_angle(self) -> f64 {
        match self {
            Design::Offset { .. } => FRAC_PI_2,
            Design::Inclined { .. } => SLIDE.0.atan2(-SLIDE.1),
        }
    }

    /// How far the rod falls short of reaching the slide at the limit: the crank pin's height
    /// `e + r` above the slide (at `phi = pi/2`, `sin phi = 1` exactly), or its distance `u h -
    /// v r` from the inclined slide (at `phi = 0`, the pin at `(r, h)`), less the rod.
    fn miss(self) -> f64 {
        match self {
            Design::Offset { r, l, e } => (e + r) - l,
            Design::Inclined { r, l, h } => (SLIDE.0 * h - SLIDE.1 * r) - l,
        }
    }

    /// The magnitude of the terms of the equation the rod's angle is solved from, the sum of
    /// the lengths in it: the loop's Y projection `e + r sin phi - l sin psi` (`|e| + r + l`);
    /// for the inclined slide, the projection free of the slider, `v X - u Y`, each projection's
    /// lengths but the slider's (`v (r + l) + u (h + r + l)`).
    fn size(self) -> f64 {
        match self {
            Design::Offset { r, l, e } => e.abs() + r + l,
            Design::Inclined { r, l, h } => SLIDE.1 * (r + l) + SLIDE.0 * (h + r + l),
        }
    }

    /// The rod's length.
    fn rod(self) -> f64 {
        match self {
            Design::Offset { l, .. } | Design::Inclined { l, .. } => l,
        }
    }

    /// The residual at rod angle `psi` of the equation the angle is solved from, computed here
    /// from the construction, over [`Design::size`]: the loop's Y projection `e + r sin phi - l
    /// sin psi`; for the inclined slide `v X - u Y`, the combination of the projections free of
    /// the slider.
    fn equation_residual(self, psi: f64) -> f64 {
        let phi = self.input();
        let f = match self {
            Design::Offset { r, l, e } => e + r * phi.sin() - l * psi.sin(),
            Design::Inclined { r, l, h } => {
                let (u, v) = SLIDE;
                v * (r * phi.cos() - l * psi.cos()) - u * (h + r * phi.sin() - l * psi.sin())
            }
        };
        f.abs() / self.size()
    }

    /// The slider at the limit position: below the crank pin (`r cos phi`, the rod vertical),
    /// or at the foot of the perpendicular from the pin `(r, h)` to the slide, `u r + v h`.
    fn slider_at_limit(self) -> f64 {
        let phi = self.input();
        match self {
            Design::Offset { r, .. } => r * phi.cos(),
            Design::Inclined { r, h, .. } => SLIDE.0 * r + SLIDE.1 * h,
        }
    }

    /// The compiled mechanism's positions at the limit's input, from a guess on the limit's
    /// side.
    fn solve(self, cfg: &NewtonConfig) -> Result<[f64; 2], Error> {
        let x = [self.input()];
        match self {
            Design::Offset { r, l, e } => OffsetSliderCrank { r, l, e }.position_flat(&x, &[1.5, 0.0], cfg),
            Design::Inclined { r, l, h } => {
                let (u, v) = SLIDE;
                InclinedSliderCrank { r, l, h, u, v }.position_flat(&x, &[2.0, 0.0], cfg)
            }
        }
        .map(|(q, _)| q)
    }
}

/// The residual tolerance `cfg` judges in: at least `16 eps`.
fn tolerance(cfg: &NewtonConfig) -> f64 {
    cfg.residual_tol.max(16.0 * f64::EPSILON)
}

/// Checks one solve of `g` against its construction, given whether the rod at the limit closes
/// the loop within the tolerance. Either a position: its angle's equation closed within the
/// tolerance of its size (plus the rounding of its few terms, `8 eps`), the rod within `free =
/// sqrt(2 tol' size / l)` of its limit angle (turning it by `t` from there opens the loop by `l
/// (1 - cos t) ~ l t² / 2`, so every angle within that closes it as well, and the rounding of
/// the lengths moves the root that far: `3e-6` rad for a rod of `1.2e-6` beside lengths of
/// `1`), and the slider within `l free` of its place at the limit (it follows the rod's
/// cosine, at most `free` there) plus the tolerance of the size. Or no assembly with the miss
/// over the equation's size as residual, to the rounding of the lengths (`4 eps`: the miss is
/// computed here from lengths rounded at the design's size).
fn check(what: &str, g: Design, closes: bool, cfg: &NewtonConfig) {
    let tol = tolerance(cfg) + 8.0 * f64::EPSILON;
    match g.solve(cfg) {
        Ok([psi, x]) => {
            assert!(closes, "{what}: a position ({psi}, {x}) where the rod misses by {:e}", g.miss() / g.size());
            let f = g.equation_residual(psi);
            assert!(f <= tol, "{what}: the angle's equation open by {f:e} of its size");
            let free = (2.0 * tol * g.size() / g.rod()).sqrt();
            let off = (psi - g.limit_angle()).abs();
            assert!(off <= free, "{what}: rod at {psi}, {off:e} from its limit angle (at most {free:e})");
            let dx = (x - g.slider_at_limit()).abs();
            let most = g.rod() * free + tol * g.size();
            assert!(dx <= most, "{what}: slider at {x:e}, {dx:e} from its place at the limit (at most {most:e})");
        }
        Err(Error::NoAssembly { residual, ref equation, .. }) => {
            assert!(!closes, "{what}: cannot be assembled (residual {residual:e}), yet the rod closes the loop");
            let want = g.miss() / g.size();
            assert!((residual - want).abs() <= 4.0 * f64::EPSILON, "{what}: residual {residual:e} against {want:e}");
            assert!(equation.starts_with("ocb."), "{what}: {equation}");
        }
        Err(e) => panic!("{what}: {e}"),
    }
}

/// The designs closing exactly at their limit in decimal, each in metres, millimetres and
/// micrometres: their rods short beside their cranks, so that the equation's `c` is a
/// difference of terms thousands of times longer than itself. Before, with the verdict
/// relative to `|c|`: the first was "cannot be assembled" in metres under the default
/// tolerance and a position in the other units; the second, at the rounding floor, "cannot be
/// assembled" in metres and millimetres and a position in micrometres; the inclined ones
/// likewise (the first in metres, the second in millimetres).
fn exact_designs() -> Vec<(&'static str, [Design; 3])> {
    let o = |r, l, e| Design::Offset { r, l, e };
    let i = |r, l, h| Design::Inclined { r, l, h };
    vec![
        ("offset, rod 0.1 mm", [o(0.5439, 0.0001, -0.5438), o(543.9, 0.1, -543.8), o(543900.0, 100.0, -543800.0)]),
        ("offset, rod 0.3 mm", [o(0.406, 0.0003, -0.4057), o(406.0, 0.3, -405.7), o(406000.0, 300.0, -405700.0)]),
        ("inclined, rod 1.2 um", [i(0.3, 0.0000012, 0.400002), i(300.0, 0.0012, 400.002), i(300000.0, 1.2, 400002.0)]),
        ("inclined, rod 1.8 um", [i(0.45, 0.0000018, 0.600003), i(450.0, 0.0018, 600.003), i(450000.0, 1.8, 600003.0)]),
        ("inclined, rod 60 um", [i(0.3, 0.00006, 0.4001), i(300.0, 0.06, 400.1), i(300000.0, 60.0, 400100.0)]),
    ]
}

/// Under the default tolerance and at the rounding floor (a residual tolerance of 0, `16 eps`),
/// a design closing exactly in decimal is its limit position in every unit: the rounding of
/// its lengths, a few `eps` of the equation's terms, is no miss.
#[test]
fn a_one_angle_limit_closing_exactly_in_decimal_is_the_limit_position_in_every_unit() {
    for cfg in [NewtonConfig::default(), NewtonConfig::default().with_residual_tol(0.0)] {
        for (name, units) in exact_designs() {
            for (unit, g) in ["m", "mm", "um"].iter().zip(units) {
                check(&format!("{name} in {unit}, tolerance {:e}", cfg.residual_tol), g, true, &cfg);
            }
        }
    }
}

/// Sizes from `1e-100` to `1e100`, all within the closed forms' range.
const SIZES: [f64; 11] = [1e-100, 1e-60, 1e-30, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e30, 1e60, 1e100];

/// Every design at every size: closing at its limit to the rounding of its lengths, the limit
/// position; its rod shortened so that it misses by 500 times the tolerance of the equation's
/// size, no assembly with that miss over the size as residual; under the default tolerance and
/// at the rounding floor.
#[test]
fn a_one_angle_limit_is_judged_alike_at_every_size() {
    for cfg in [NewtonConfig::default(), NewtonConfig::default().with_residual_tol(0.0)] {
        let tol = tolerance(&cfg);
        for (name, [g, ..]) in exact_designs() {
            let short = g.shorter(500.0 * tol * g.size());
            for k in SIZES {
                let at = format!("{name}, size {k:e}, tolerance {:e}", cfg.residual_tol);
                check(&format!("{at}, closing"), g.scaled(k), true, &cfg);
                check(&format!("{at}, missing by 500 tolerances"), short.scaled(k), false, &cfg);
            }
        }
    }
}

/// A rod within the tolerance of nothing (`1e-20` beside a crank and offset of `1`) whose crank
/// pin lies within the tolerance of the slide (`4.4e-16` above it, at `phi = pi/2`): the rod
/// cannot reach the slide, but every angle of it closes the loop within the tolerance of its
/// lengths (checked here over a turn), so the angle is not determined: singular, as Newton finds
/// a column of `1e-20` beside rows of `2`, not "cannot be assembled" (its residual the whole
/// miss over `|c| + l`, `1`, before). Every angle closing the equation is what the dyad's
/// closed form reports singular too.
#[test]
fn a_rod_every_angle_of_which_closes_the_loop_is_singular() {
    let cfg = NewtonConfig::default();
    let g = Design::Offset { r: 1.0, l: 1e-20, e: -1.0 + 4.0 * f64::EPSILON };
    assert!(g.miss() > 0.0, "the rod must miss the slide");
    for k in 0..360 {
        let psi = f64::from(k).to_radians();
        let f = g.equation_residual(psi);
        assert!(f <= cfg.residual_tol, "angle {psi}: the equation open by {f:e} of its size");
    }
    match g.solve(&cfg) {
        Err(Error::Singular { .. }) => {}
        other => panic!("{other:?}"),
    }
}
