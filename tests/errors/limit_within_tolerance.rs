//! Closed-form dyads at a limit position within the residual tolerance, in metres, millimetres
//! and micrometres: the verdict (a position, or "cannot be assembled") is the same in every
//! unit and is Newton's: a position whose links laid in line close the loop within the
//! tolerance of its size is the limit position, one that misses by more cannot be assembled,
//! with the miss over the dyad's size as residual.
//!
//! Each design is a four-bar at its crank's angle `pi` (or the same dyad on a slider at `s =
//! 0`) whose coupler and rocker, in line, fall short of the centres `B` and `D` by `delta`: the
//! reference is that construction, `|BD| = b + c + delta`, whose in-line position is `beta = 0`,
//! `gamma = pi` and whose least residual is `delta` (its gap over the dyad's size `b + c +
//! |BD|`). One of the two links is 1 µm beside lengths of 0.4 m. The verdict was taken in the
//! dyad's equation's coefficients, whose allowance scaled with the short link: a short coupler
//! (the dyad's first link) at a miss of `5e-14` of its size was "cannot be assembled" in every
//! unit, and at a miss of zero in decimal, in metres only (where the rounding of the lengths
//! leaves `1e-17` m, beyond its allowance of `1e-18`); a short rocker at a miss of `5e-10` of
//! its size was a position with the loop open by `4e-10` m and no error.

use kinloop::{Error, Mechanism, NewtonConfig};
use std::f64::consts::PI;

kinloop::mechanism! {
    /// A four-bar driven by its crank `a` about `A = (0, 0)`: coupler `b` at `beta`, rocker `c`
    /// at `gamma` about `D = (d, 0)`.
    pub struct InLineFourBar {
        params a, b, c, d;
        input phi;
        unknowns beta = 0.1, gamma = 3.0;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

kinloop::mechanism! {
    /// The four-bar's dyad with its first centre `B = (s, 0)` on a slider along the frame:
    /// the centres' offset has a zero component, a coefficient folded in the closed form.
    pub struct InLineSliderDyad {
        params b, c, d;
        input s;
        unknowns beta = 0.1, gamma = 3.0;
        loop sbcd: (s, 0) + b @ beta == (d, 0) + c @ gamma;
    }
}

/// A design in one unit: the crank `a` and frame `d` (so that `|BD| = a + d` at `phi = pi`,
/// and `|BD| = d` for the slider at `s = 0`), the coupler `b` and rocker `c`, as written in
/// decimal, and the intended miss `delta` (in the same unit).
#[derive(Clone, Copy, Debug)]
struct Design {
    a: f64,
    b: f64,
    c: f64,
    d: f64,
    delta: f64,
}

/// The designs, each in metres, millimetres and micrometres, with whether their links in line
/// close the loop within the default residual tolerance (`1e-12` of the dyad's size, 0.8 m).
fn designs() -> Vec<(&'static str, bool, [Design; 3])> {
    let d = |a, b, c, d, delta| Design { a, b, c, d, delta };
    vec![
        (
            "short coupler, missing by 4e-14 m",
            true,
            [
                d(0.1, 0.000001, 0.39999899999996, 0.3, 4e-14),
                d(100.0, 0.001, 399.99899999996, 300.0, 4e-11),
                d(100000.0, 1.0, 399998.99999996, 300000.0, 4e-8),
            ],
        ),
        (
            "short coupler, closing exactly in decimal",
            true,
            [
                d(0.1, 0.000001, 0.399999, 0.3, 0.0),
                d(100.0, 0.001, 399.999, 300.0, 0.0),
                d(100000.0, 1.0, 399999.0, 300000.0, 0.0),
            ],
        ),
        (
            "short rocker, missing by 4e-14 m",
            true,
            [
                d(0.1, 0.39999899999996, 0.000001, 0.3, 4e-14),
                d(100.0, 399.99899999996, 0.001, 300.0, 4e-11),
                d(100000.0, 399998.99999996, 1.0, 300000.0, 4e-8),
            ],
        ),
        (
            "short rocker, missing by 4e-10 m",
            false,
            [
                d(0.1, 0.3999989996, 0.000001, 0.3, 4e-10),
                d(100.0, 399.9989996, 0.001, 300.0, 4e-7),
                d(100000.0, 399998.9996, 1.0, 300000.0, 4e-4),
            ],
        ),
        (
            "short coupler, missing by 4e-10 m",
            false,
            [
                d(0.1, 0.000001, 0.3999989996, 0.3, 4e-10),
                d(100.0, 0.001, 399.9989996, 300.0, 4e-7),
                d(100000.0, 1.0, 399998.9996, 300000.0, 4e-4),
            ],
        ),
    ]
}

/// The largest component of the loop's residual at `(beta, gamma)` with `B = (bx, 0)` and `D =
/// (d, 0)`, computed here from the construction (not by the library), over the loop's size
/// `|bx| + b + c + d`.
fn loop_residual(bx: f64, g: &Design, beta: f64, gamma: f64) -> f64 {
    let x = bx + g.b * beta.cos() - g.d - g.c * gamma.cos();
    let y = g.b * beta.sin() - g.c * gamma.sin();
    x.abs().max(y.abs()) / (bx.abs() + g.b + g.c + g.d)
}

/// Checks one solve against its design: where the links in line close the loop within the
/// tolerance `tol` (`1e-12` by default, `16 eps` at the rounding floor), a position closing it
/// as well (`tol` of the loop, plus the rounding of its four terms, `8 eps`) near the links in line (`beta = 0`, `gamma = pi`): at
/// the fold, turning the short link (`l`) by `t` opens the loop by about `l t² / 2`, so every
/// angle within `sqrt(2 tol size / l)` closes it as well (`1.3e-3` rad here; where rounding
/// lengthens the links into a triangle, in millimetres, the root is `6.9e-6` rad off line);
/// where they miss by more, no assembly with the residual `delta / (b + c + |BD|)` (to `1e-4`
/// of itself: the lengths' rounding, `1e-16` of the size, over a gap of `5e-10`).
fn check(what: &str, closes: bool, g: &Design, bx: f64, got: Result<[f64; 2], Error>, tol: f64) {
    let size = g.b + g.c + (g.d - bx);
    match got {
        Ok([beta, gamma]) => {
            assert!(closes, "{what}: solved ({beta}, {gamma}), yet the links in line miss by {:e}", g.delta / size);
            let tol = tol + 8.0 * f64::EPSILON;
            let r = loop_residual(bx, g, beta, gamma);
            assert!(r <= tol, "{what}: loop open by {r:e} of its size");
            let free = (2.0 * tol * size / g.b.min(g.c)).sqrt();
            assert!(beta.sin().abs() <= free && beta.cos() > 0.0, "{what}: beta {beta}, {free:e} from 0 at most");
            assert!((gamma - PI).abs() <= free, "{what}: gamma {gamma}, {free:e} from pi at most");
        }
        Err(Error::NoAssembly { residual, ref equation, .. }) => {
            assert!(!closes, "{what}: cannot be assembled, yet the links in line close it (residual {residual:e})");
            let want = g.delta / size;
            assert!((residual - want).abs() <= 1e-4 * want, "{what}: residual {residual:e} against {want:e}");
            assert!(equation.contains("abcd") || equation.contains("sbcd"), "{what}: {equation}");
        }
        Err(e) => panic!("{what}: {e}"),
    }
}

/// The four-bar at `phi = pi` and the slider's dyad at `s = 0`, every design in every unit: the
/// verdict of the construction in each, whichever of the two links is short.
#[test]
fn a_dyad_within_the_tolerance_of_its_limit_is_the_limit_position_in_every_unit() {
    for (name, closes, units) in designs() {
        solve_in_every_unit(name, closes, &units, &NewtonConfig::default());
    }
}

/// At the rounding floor (a residual tolerance of 0, which allows `16 eps` of the size), a
/// dyad closing exactly in decimal is still its limit position in every unit, the short link
/// the coupler or the rocker: the rounding of its lengths, a few `eps` of its size, is no miss.
#[test]
fn a_dyad_closing_exactly_in_decimal_is_the_limit_position_at_the_rounding_floor() {
    let floor = NewtonConfig::default().with_residual_tol(0.0);
    let d = |a, b, c, d| Design { a, b, c, d, delta: 0.0 };
    let exact = [
        (
            "short coupler",
            [d(0.1, 0.000001, 0.399999, 0.3), d(100.0, 0.001, 399.999, 300.0), d(1e5, 1.0, 399999.0, 3e5)],
        ),
        (
            "short rocker",
            [d(0.1, 0.399999, 0.000001, 0.3), d(100.0, 399.999, 0.001, 300.0), d(1e5, 399999.0, 1.0, 3e5)],
        ),
    ];
    for (name, units) in exact {
        solve_in_every_unit(name, true, &units, &floor);
    }
}

/// [`check`]s the four-bar at `phi = pi` and the slider's dyad at `s = 0` of a design in each
/// unit, under `cfg`.
fn solve_in_every_unit(name: &str, closes: bool, units: &[Design; 3], cfg: &NewtonConfig) {
    let tol = cfg.residual_tol.max(16.0 * f64::EPSILON);
    for (unit, g) in ["m", "mm", "µm"].iter().zip(units) {
        let four_bar = InLineFourBar { a: g.a, b: g.b, c: g.c, d: g.d };
        let got = four_bar.position_flat(&[PI], &[0.1, 3.0], cfg).map(|(q, _)| q);
        check(&format!("four-bar, {name}, in {unit}"), closes, g, -g.a, got, tol);
        // The slider's dyad: `B = (0, 0)`, `D = (a + d, 0)`, the same lengths.
        let slider = InLineSliderDyad { b: g.b, c: g.c, d: g.a + g.d };
        let on_slider = Design { d: g.a + g.d, ..*g };
        let got = slider.position_flat(&[0.0], &[0.1, 3.0], cfg).map(|(q, _)| q);
        check(&format!("slider's dyad, {name}, in {unit}"), closes, &on_slider, 0.0, got, tol);
    }
}
