//! `assembly_near`: where a one-input mechanism assembles nearest an input at which it does
//! not, checked against the four-bar's limit positions by the law of cosines (coupler and rocker
//! stretched out or folded: the distance from the crank pin to the rocker's pivot equals their
//! sum or difference), at several sizes, by closed forms and by Newton's method.

use kinloop::Error;
use kinloop::paths::assembles::{ASSEMBLY_SAMPLES, assembly_along, assembly_near};
use kinloop_fixtures::{FiveBar, FourBar};
use std::f64::consts::{PI, TAU};

use crate::support::{four_bar_limit, tol};
// The four-bar solved by Newton's method: a far guess fails to converge rather than to
// assemble, which the search counts as not assembling there.
use crate::sweep_api::NewtonFourBar;

kinloop::mechanism! {
    /// A dyad on a slide: its input is a length, whose "turn" the search cannot sample.
    pub struct SlideDyad {
        params b = 2.0, c = 1.5, h = 1.0;
        input s;
        unknowns beta = 0.5, gamma = 1.5;
        loop slide: (s, 0) + b @ beta == (0, h) + c @ gamma;
    }
}

/// Coupler and rocker (2.5 + 1.5 = 4) fall short of frame and crank in line (3.2 + 1): the crank
/// rocks between the angles where `|A + a e(phi) - D| = b + c`.
fn short_reach(scale: f64) -> FourBar {
    FourBar { a: scale, b: 2.5 * scale, c: 1.5 * scale, d: 3.2 * scale }
}

#[test]
fn a_four_bar_beyond_its_reach_is_told_the_stretch_between_its_limit_positions() {
    let lim = four_bar_limit(1.0, 3.2, 4.0);
    for scale in [1e-6, 1.0, 1e6] {
        let m = short_reach(scale);
        for at in [3.1, -3.0, 2.5] {
            assert!(matches!(m.position(at, &m.guess(at)), Err(Error::NoAssembly { .. })), "{at}");
            let near = assembly_near(&m, [at], ASSEMBLY_SAMPLES).unwrap().expect("it assembles");
            assert_close!(near.reach.to[0], lim, tol::LOCATED, "{scale} {at}: {near:?}");
            assert_close!(near.reach.from[0], -lim, tol::LOCATED, "{scale} {at}: {near:?}");
            assert!(near.reach.from_event.is_some() && near.reach.to_event.is_some(), "{near:?}");
            assert!(!near.turns_fully());
            // The sample nearest `at` inside the stretch: within a degree of its near end.
            let end = if at > 0.0 { lim } else { -lim };
            assert!((near.found[0] - end).abs() <= TAU / ASSEMBLY_SAMPLES as f64, "{at}: {near:?}");
            assert!(m.position(near.found[0], &m.guess(near.found[0])).is_ok());
        }
    }
}

#[test]
fn the_stretch_is_the_one_on_the_turn_of_the_input_asked_for() {
    let m = short_reach(1.0);
    let lim = four_bar_limit(1.0, 3.2, 4.0);
    for turns in [-3.0, 5.0] {
        let at = 3.1 + turns * TAU;
        let near = m.assembly_near(at).unwrap().expect("it assembles");
        // The copy of the stretch on `at`'s turn (its end 0.69 from `at`; the next turn's is 0.77).
        let centre = (near.reach.from.phi + near.reach.to.phi) / 2.0;
        assert_close!(centre, turns * TAU, <= 1e-9, "{near:?}");
        assert_close!(near.reach.to.phi - near.reach.from.phi, 2.0 * lim, tol::LOCATED, "{near:?}");
        assert!((near.found.phi - at).abs() <= PI);
    }
}

#[test]
fn a_four_bar_that_folds_short_assembles_on_the_far_side() {
    // Coupler less rocker (3.5 - 0.8 = 2.7) beyond the shortest distance from crank pin to
    // pivot (3.2 - 1): the links close only where that distance is at least 2.7, about pi.
    let m = FourBar { a: 1.0, b: 3.5, c: 0.8, d: 3.2 };
    let lim = four_bar_limit(1.0, 3.2, 2.7);
    let near = assembly_near(&m, [0.0], 360).unwrap().expect("it assembles");
    assert_close!(near.reach.from[0], lim, tol::LOCATED, "{near:?}");
    assert_close!(near.reach.to[0], TAU - lim, tol::LOCATED, "{near:?}");
    assert!((near.found[0] - lim).abs() <= TAU / 360.0, "{near:?}");
}

#[test]
fn where_it_assembles_the_input_itself_is_found_and_a_crank_turns_fully() {
    // A crank-rocker: the crank turns fully.
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    let near = assembly_near(&m, [0.7], 360).unwrap().expect("it assembles");
    assert_eq!(near.found, [0.7]);
    assert!(near.turns_fully(), "{near:?}");
    assert_close!(near.reach.from[0], 0.7 - TAU, 1e-15);
    assert_close!(near.reach.to[0], 0.7 + TAU, 1e-15);
    // Inside the stretch of a rocking crank: found at once, the same stretch.
    let lim = four_bar_limit(1.0, 3.2, 4.0);
    let near = assembly_near(&short_reach(1.0), [0.3], 360).unwrap().expect("it assembles");
    assert_eq!(near.found, [0.3]);
    assert_close!(near.reach.to[0], lim, tol::LOCATED, "{near:?}");
}

#[test]
fn links_that_close_nowhere_are_none() {
    // The frame longer than the other three links together.
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 10.0 };
    assert_eq!(assembly_near(&m, [0.0], 360).unwrap(), None);
    assert_eq!(m.assembly_near(2.0).unwrap(), None);
}

#[test]
fn newtons_method_finds_the_same_stretch() {
    let m = NewtonFourBar { a: 1.0, b: 2.5, c: 1.5, d: 3.2 };
    let lim = four_bar_limit(1.0, 3.2, 4.0);
    assert!(m.position(3.1, &m.guess(3.1)).is_err());
    let near = assembly_near(&m, [3.1], 360).unwrap().expect("it assembles");
    assert_close!(near.reach.to[0], lim, tol::LOCATED, "{near:?}");
    assert_close!(near.reach.from[0], -lim, tol::LOCATED, "{near:?}");
}

/// Asserts an `Error::InvalidArgument` whose message contains `words`.
fn invalid<T: std::fmt::Debug>(r: Result<T, Error>, words: &str) {
    match r {
        Err(Error::InvalidArgument(text)) => assert!(text.contains(words), "{text}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn what_it_cannot_search_is_an_error() {
    let m = short_reach(1.0);
    invalid(assembly_near(&m, [0.0], 1), "at least 2");
    invalid(assembly_near(&m, [0.0], kinloop::analysis::MAX_SAMPLES + 1), "at most");
    invalid(assembly_near(&m, [1e300], 360), "too large");
    assert!(matches!(assembly_near(&m, [f64::NAN], 360), Err(Error::NonFinite { .. })));
    invalid(assembly_near(&FiveBar::default(), [0.0, 1.0], 360), "2 inputs");
    invalid(assembly_near(&SlideDyad::default(), [0.5], 360), "not an angle");
}

#[test]
fn a_start_a_hair_inside_a_limit_position_is_passed_over() {
    // Solved (its pivot ratio above the point solve's tolerance), but nearer the limit position
    // than a sweep starts from: the search goes on to the next sample.
    let m = short_reach(1.0);
    let lim = four_bar_limit(1.0, 3.2, 4.0);
    let at = lim - 1e-13;
    let q = m.position(at, &m.guess(at)).expect("assembles a hair inside").0;
    let start = m.reachable(at, 0.1, &q, 3);
    assert!(matches!(start, Err(Error::NearSingular { .. })), "{start:?}");
    let near = assembly_near(&m, [at], 360).unwrap().expect("it assembles");
    assert_eq!(near.found, [at - TAU / 360.0]);
    assert_close!(near.reach.to[0], lim, tol::LOCATED, "{near:?}");
    assert_close!(near.reach.from[0], -lim, tol::LOCATED, "{near:?}");
}

#[test]
fn a_path_that_starts_outside_is_told_where_it_enters() {
    // From 3 to 5 rad the short-reach four-bar enters its stretch at 2 pi - lim (the next
    // turn's copy of -lim), at every size.
    let lim = four_bar_limit(1.0, 3.2, 4.0);
    for scale in [1e-6, 1.0, 1e6] {
        let m = short_reach(scale);
        let entry = assembly_along(&m, [3.0], [5.0], 100).unwrap().expect("it enters");
        assert_close!(entry.at[0], TAU - lim, tol::LOCATED, "{scale}: {entry:?}");
        assert_close!(entry.fraction, (TAU - lim - 3.0) / 2.0, tol::LOCATED, "{entry:?}");
        // The first of the samples 0.02 apart past the entry, where a sweep starts.
        let first = 3.0 + 0.02 * ((TAU - lim - 3.0) / 0.02).ceil();
        assert_close!(entry.sample[0], first, 1e-15, "{entry:?}");
        assert!(m.position(entry.sample[0], &m.guess(entry.sample[0])).is_ok());
    }
    // Where `from` assembles, it is the entry; where the path stays outside, none.
    let m = short_reach(1.0);
    let entry = assembly_along(&m, [0.5], [5.0], 10).unwrap().expect("it assembles");
    assert_eq!((entry.fraction, entry.at, entry.sample), (0.0, [0.5], [0.5]));
    assert_eq!(assembly_along(&m, [2.5], [3.8], 100).unwrap(), None);
}

#[test]
fn a_five_bars_path_enters_where_its_links_reach() {
    // The five-bar's base 5 (links 1, 2.5, 2.2, 1.2): at th1 = pi, th2 = 0 the cranks' pins are
    // 7.2 apart, beyond the coupler links' 4.7; at th1 = 0, th2 = pi, 2.8. Along the path the
    // pins' distance first falls to 4.7 where the links stretch out.
    let m = FiveBar { d: 5.0, ..FiveBar::default() };
    let (from, to) = ([PI, 0.0], [0.0, PI]);
    let entry = assembly_along(&m, from, to, 50).unwrap().expect("it enters");
    let gap = |t: f64| {
        let (t1, t2) = (PI * (1.0 - t), PI * t);
        let (bx, by) = (m.a * t1.cos(), m.a * t1.sin());
        let (dx, dy) = (m.d + m.e * t2.cos(), m.e * t2.sin());
        (dx - bx).hypot(dy - by) - (m.b + m.c)
    };
    // The distance's root by bisection in plain geometry: decreasing along the path there.
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) > 0.0 { lo = mid } else { hi = mid }
    }
    assert_close!(entry.fraction, hi, tol::LOCATED, "{entry:?}");
    assert_close!(entry.at[0], PI * (1.0 - hi), tol::LOCATED, "{entry:?}");
    assert_close!(entry.at[1], PI * hi, tol::LOCATED, "{entry:?}");
}

#[test]
fn what_a_path_cannot_search_is_an_error() {
    let m = short_reach(1.0);
    invalid(assembly_along(&m, [0.0], [1.0], 0), "0 samples");
    invalid(assembly_along(&m, [1.0], [1.0], 10), "`from` equals `to`");
    invalid(assembly_along(&m, [0.0], [1.0], kinloop::analysis::MAX_SAMPLES + 1), "at most");
    assert!(matches!(assembly_along(&m, [0.0], [f64::INFINITY], 10), Err(Error::NonFinite { .. })));
}
