//! `assembly_near`: where a one-input mechanism assembles nearest an input at which it does
//! not, checked against the four-bar's limit positions by the law of cosines (coupler and rocker
//! stretched out or folded: the distance from the crank pin to the rocker's pivot equals their
//! sum or difference), at several sizes, by closed forms and by Newton's method.

use kinloop::paths::assembles::{ASSEMBLY_SAMPLES, assembly_along, assembly_near};
use kinloop::{Error, Named, NewtonConfig};
use kinloop_fixtures::{FiveBar, FourBar};
use std::f64::consts::{PI, TAU};

use crate::support::{four_bar_limit, tol};
// The four-bar solved by Newton's method: a far guess may fail to converge rather than to
// assemble, which tells nothing of whether it assembles there (an error where the search's
// answer depends on it).
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

/// At `pi` the short-reach four-bar (symmetric about `phi = 0`) is as far from its stretch
/// `|phi| <= lim` one way as the other: the samples `pi + j h` and `pi - j h` assemble alike, and
/// the search answers the one above `pi`, at every count of samples.
#[test]
fn of_two_samples_as_near_the_greater_is_found() {
    let m = short_reach(1.0);
    let lim = four_bar_limit(1.0, 3.2, 4.0);
    let assembles = |x: f64| m.position(x, &m.guess(x)).is_ok();
    for samples in [90, 360, 1000] {
        let h = TAU / samples as f64;
        let near = assembly_near(&m, [PI], samples).unwrap().expect("it assembles");
        let j = ((near.found[0] - PI) / h).round();
        assert!(j >= 1.0, "{samples}: {near:?}");
        assert_eq!(near.found, [PI + j * h], "{samples}");
        // A tie: the sample as near below assembles too, and none nearer does either way.
        assert!(assembles(PI - j * h), "{samples}: {near:?}");
        assert!(!assembles(PI + (j - 1.0) * h) && !assembles(PI - (j - 1.0) * h), "{samples}");
        // The stretch it reaches is the next turn's copy, above `pi`.
        assert_close!(near.reach.from[0], TAU - lim, tol::LOCATED, "{near:?}");
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

/// Newton's method far from any position stalls and says the loops cannot close (`NoAssembly`):
/// links that close nowhere, or an input beyond a rocker's limit, are still "nowhere" (`None`,
/// no mode), not the error of a search that cannot tell.
#[test]
fn links_that_close_nowhere_by_newton_are_none() {
    for d in [6.6, 10.0, 1e3] {
        let m = NewtonFourBar { a: 1.0, b: 3.0, c: 2.5, d };
        for at in [0.0, 1.0, 2.0, 3.0, -2.5] {
            assert_eq!(assembly_near(&m, [at], 360).unwrap(), None, "d {d}, at {at}");
            assert!(m.assembly_modes(at).unwrap().is_empty(), "d {d}, at {at}");
        }
        assert_eq!(assembly_along(&m, [0.0], [6.0], 100).unwrap(), None, "d {d}");
    }
    let rocker = NewtonFourBar { a: 1.0, b: 2.5, c: 1.5, d: 3.2 };
    assert!(rocker.assembly_modes(3.1).unwrap().is_empty());
    assert_eq!(assembly_along(&rocker, [2.5], [3.8], 100).unwrap(), None);
}

/// A four-bar that assembles at every input, its Newton solves allowed 0 to 2 iterations: no
/// solve succeeds, and the searches answered "nowhere" (no mode, `None`), which is wrong and
/// says nothing of the settings. They now say they cannot tell: the solves' `NoConvergence`,
/// naming the iterations.
#[test]
fn a_solver_too_tight_to_tell_is_an_error_not_nowhere() {
    let m = NewtonFourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    assert!(m.assembly_near(0.4).unwrap().is_some() && m.assembly_modes(0.4).unwrap().len() == 2);
    for iterations in 0..=2 {
        let tight = m.with_config(NewtonConfig::default().with_max_iterations(iterations)).unwrap();
        let no_convergence = |what: &str, e: Error| {
            assert!(matches!(e, Error::NoConvergence { .. }), "{iterations} iterations, {what}: {e:?}");
            assert!(e.to_string().contains("max_iterations"), "{e}");
        };
        no_convergence("modes", tight.assembly_modes(0.4).expect_err("cannot tell"));
        no_convergence("near", assembly_near(&tight, [0.4], 360).expect_err("cannot tell"));
        no_convergence("along", assembly_along(&tight, [0.0], [1.0], 10).expect_err("cannot tell"));
    }
}

/// The same four-bar allowed 4 iterations solves from its declared guess only between about
/// 20 and 113 degrees, though it assembles at every input: asked about 0, the search answered
/// 20 degrees as "the nearest assembly", and the path from 0 entered at about 20 degrees. The
/// nearer samples' solves ran out of iterations, which tells nothing of whether they assemble:
/// the answer is their `NoConvergence`. Where the input itself solves, it is still the answer.
#[test]
fn a_nearer_sample_that_ran_out_of_iterations_is_an_error_not_a_farther_answer() {
    let m = NewtonFourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    let tight = m.with_config(NewtonConfig::default().with_max_iterations(4)).unwrap();
    let deg = |d: f64| d.to_radians();
    // It assembles at 0 (by default), the tight solve there runs out, and one 20 degrees on solves.
    assert!(m.position(0.0, &m.guess(0.0)).is_ok());
    assert!(matches!(tight.position(0.0, &tight.guess(0.0)), Err(Error::NoConvergence { .. })));
    assert!(tight.position(deg(20.0), &tight.guess(deg(20.0))).is_ok());
    let no_convergence = |what: &str, e: Error| {
        assert!(matches!(e, Error::NoConvergence { .. }), "{what}: {e:?}");
        assert!(e.to_string().contains("max_iterations"), "{e}");
    };
    no_convergence("near", assembly_near(&tight, [0.0], 360).expect_err("cannot tell"));
    no_convergence("along", assembly_along(&tight, [0.0], [1.0], 10).expect_err("cannot tell"));
    let near = assembly_near(&tight, [deg(60.0)], 360).unwrap().expect("it assembles");
    assert_eq!(near.found, [deg(60.0)]);
    let entry = assembly_along(&tight, [deg(60.0)], [deg(200.0)], 10).unwrap().expect("it assembles");
    assert_eq!(entry.at, [deg(60.0)]);
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
    // than a sweep starts from: the search goes on to the next sample. The sweep from it is a
    // singular start, as `SweepConfig::singular_pivot` says of a first sample below it, at the
    // start: it was a pass "near a singular position" a step on, with the advice to lower
    // `singular_pivot` that a slide brushing its pivot takes.
    let m = short_reach(1.0);
    let lim = four_bar_limit(1.0, 3.2, 4.0);
    let at = lim - 1e-13;
    let q = m.position(at, &m.guess(at)).expect("assembles a hair inside").0;
    let start = m.reachable(at, 0.1, &q, 3);
    let Err(Error::SingularStart { pivot_ratio, singular_pivot, at: ref located }) = start else { panic!("{start:?}") };
    assert!(pivot_ratio < singular_pivot, "{start:?}");
    assert_eq!(located.inputs[0].1, at, "{start:?}");
    let first = m.kinematics(at, &q).unwrap();
    assert_eq!(pivot_ratio, first.health.min_pivot);
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
    // Finite ends whose difference overflows: no input on the path is finite (the first,
    // `from + 0 * inf`, is NaN), which was an error about a NaN input nobody gave.
    invalid(assembly_along(&m, [-1e308], [1e308], 10), "overflows");
    invalid(assembly_along(&m, [f64::MAX], [-f64::MAX], 1), "overflows");
}

/// Where a four-bar closes within one turn of its crank, by the law of cosines alone: the
/// crank pin lies `r(phi) = sqrt(a^2 + d^2 - 2 a d cos phi)` from the rocker's pivot, and
/// coupler and rocker reach it exactly where `|b - c| <= r <= b + c`, i.e. where
/// `cos h <= cos phi <= cos l` with `h` the limit position where they stretch out
/// (`r = b + c`) and `l` the one where they fold (`r = |b - c|`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Closes {
    /// Everywhere: the crank turns fully.
    Whole,
    /// On `[-h, h]`: folded never, stretched out at both ends.
    Stretched,
    /// On `[l, 2 pi - l]`: stretched out never, folded at both ends.
    Folded,
    /// On `[l, h]` and `[-h, -l]`: each stretch ends once folded, once stretched out.
    TwoStretches,
    /// Nowhere.
    Nowhere,
}

/// The closed form of one four-bar: its class and its stretches of assembly on one turn
/// (`lo < hi`, each shorter than a turn; none for `Whole` and `Nowhere`).
#[derive(Debug)]
struct Closure {
    class: Closes,
    stretches: Vec<(f64, f64)>,
}

/// How near a limit position (in radians) a sample may be found, or passed over: a point solve
/// or a sweep's start there is a matter of the library's tolerances (a sweep refuses to start
/// where the coupler and rocker are within about 1e-6 rad of lying in line, some 1e-12 rad of
/// crank from the limit position), which the closed form cannot predict. Inputs drawn at random
/// practically never fall that near one: a start a hair inside has a test of its own above.
const NEAR_LIMIT: f64 = 1e-6;

impl Closure {
    /// `None` near a change of class (an end's cosine within 1e-3 of +-1 or of the other end's,
    /// where stretches are born, merge or vanish), or where a stretch is narrower than two of
    /// the search's samples apart (which the search may miss, as it documents).
    fn of(a: f64, b: f64, c: f64, d: f64) -> Option<Self> {
        let cos_h = (a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d);
        let cos_l = (a * a + d * d - (b - c) * (b - c)) / (2.0 * a * d);
        let near = |u: f64, v: f64| (u - v).abs() < 1e-3;
        if [cos_h, cos_l].into_iter().any(|v| near(v, 1.0) || near(v, -1.0)) || near(cos_h, cos_l) {
            return None;
        }
        let (h, l) = (cos_h.acos(), cos_l.acos());
        let (class, stretches) = if cos_h > 1.0 || cos_l < -1.0 {
            (Closes::Nowhere, vec![])
        } else if cos_h < -1.0 && cos_l > 1.0 {
            (Closes::Whole, vec![])
        } else if cos_l > 1.0 {
            (Closes::Stretched, vec![(-h, h)])
        } else if cos_h < -1.0 {
            (Closes::Folded, vec![(l, TAU - l)])
        } else {
            (Closes::TwoStretches, vec![(l, h), (-h, -l)])
        };
        let narrowest = stretches.iter().map(|(lo, hi)| hi - lo).fold(f64::INFINITY, f64::min);
        (narrowest > 2.0 * TAU / ASSEMBLY_SAMPLES as f64).then_some(Closure { class, stretches })
    }

    /// The limit positions on one turn: every end of every stretch.
    fn limits(&self) -> impl Iterator<Item = f64> + '_ {
        self.stretches.iter().flat_map(|&(lo, hi)| [lo, hi])
    }

    /// How far `x` is from the nearest limit position, modulo turns (infinite where none).
    fn off_limit(&self, x: f64) -> f64 {
        self.limits()
            .map(|y| {
                let r = (x - y).rem_euclid(TAU);
                r.min(TAU - r)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The stretch holding `x` (to within `slack`), shifted onto `x`'s turn.
    fn stretch_of(&self, x: f64, slack: f64) -> Option<(f64, f64)> {
        self.stretches.iter().find_map(|&(lo, hi)| {
            let shift = TAU * ((x - 0.5 * (lo + hi)) / TAU).round();
            let (lo, hi) = (lo + shift, hi + shift);
            (lo - slack <= x && x <= hi + slack).then_some((lo, hi))
        })
    }

    /// Whether the four-bar closes at `x`: `Some` away from limit positions, `None` within
    /// `NEAR_LIMIT` of one.
    fn closes_at(&self, x: f64) -> Option<bool> {
        match self.class {
            Closes::Whole => Some(true),
            Closes::Nowhere => Some(false),
            _ if self.off_limit(x) < NEAR_LIMIT => None,
            _ => Some(self.stretch_of(x, 0.0).is_some()),
        }
    }
}

/// A few hundred four-bars of random proportions, sizes and inputs against the closed form
/// above: the search's answer is `None` exactly where the links close nowhere; otherwise it is
/// the first sample, in the documented order (the input, then one spacing up, one down, two up,
/// ...), at which the links close, and its stretch runs between the closed form's limit
/// positions on that sample's turn, or a turn each way where the crank turns fully.
#[test]
fn random_four_bars_assemble_where_the_law_of_cosines_says() {
    let spacing = TAU / ASSEMBLY_SAMPLES as f64;
    let mut rng = crate::support::Xorshift(0x0a55_e3b1_e5ee_d001);
    let mut counts = [0usize; 5];
    let mut skipped = 0;
    for _ in 0..400 {
        // Proportions spread over a factor of ten about 1, which gives every class a share; the
        // answer is claimed the same at every size, so the size is drawn apart from them.
        let [a, b, c, d] = [(); 4].map(|_| 10f64.powf(rng.unit() - 0.5));
        let scale = [1e-6, 1.0, 1e6][(3.0 * rng.unit()) as usize];
        // Several turns either side of 0: the stretch is the copy on the input's turn.
        let at = 4.0 * PI * (2.0 * rng.unit() - 1.0);
        let Some(set) = Closure::of(a, b, c, d) else {
            skipped += 1;
            continue;
        };
        counts[set.class as usize] += 1;
        let m = FourBar { a: a * scale, b: b * scale, c: c * scale, d: d * scale };
        let case = format!("{m:?} at {at}: {set:?}");

        // The point solve from the declared guess agrees with the closed form at the input (a
        // check of the closed form as much as of the library).
        match (set.closes_at(at), m.position(at, &m.guess(at))) {
            (Some(true), Err(e)) => panic!("{case}: closes by the law of cosines, yet {e}"),
            (Some(false), Ok(_)) => panic!("{case}: closes nowhere by the law of cosines, yet solves"),
            (Some(false), Err(e)) => assert!(matches!(e, Error::NoAssembly { .. }), "{case}: {e}"),
            _ => {}
        }

        let near = assembly_near(&m, [at], ASSEMBLY_SAMPLES).unwrap_or_else(|e| panic!("{case}: {e}"));
        let Some(near) = near else {
            assert_eq!(set.class, Closes::Nowhere, "{case}: none found");
            continue;
        };
        assert_ne!(set.class, Closes::Nowhere, "{case}: found {near:?}");
        let found = near.found[0];

        // The samples in the search's order, up to the first that surely closes: the answer is
        // one of them, the last unless a sample within a hair of a limit position came first
        // (found, or passed over where a sweep cannot start from it).
        let order = std::iter::once(0.0).chain((1..=ASSEMBLY_SAMPLES / 2).flat_map(|j| [j as f64, -(j as f64)]));
        let mut candidates = vec![];
        for j in order {
            let x = at + j * spacing;
            match set.closes_at(x) {
                Some(false) => {}
                Some(true) => {
                    candidates.push(x);
                    break;
                }
                None => candidates.push(x),
            }
        }
        assert!(candidates.contains(&found), "{case}: found {found}, expected one of {candidates:?}");
        assert!(m.position(found, &m.guess(found)).is_ok(), "{case}: found {found} does not solve");
        if set.closes_at(at) == Some(true) {
            assert_eq!(found, at, "{case}: the input itself closes");
        }
        // The same, as distances: no nearer than the nearest point where the links close, and
        // at most a spacing beyond it (two, where a sample a hair inside was passed over).
        let gap = if set.closes_at(at) == Some(true) { 0.0 } else { set.off_limit(at) };
        let passed_over = if candidates.len() > 1 { spacing } else { 0.0 };
        let off = (found - at).abs();
        assert!(off >= gap - NEAR_LIMIT, "{case}: found {found}, nearer than the stretch {gap}");
        assert!(off <= gap + spacing + passed_over + 1e-12, "{case}: found {found}, {off} from the input");

        if set.class == Closes::Whole {
            assert!(near.turns_fully(), "{case}: {near:?}");
            // No limit position: the search's ends, a turn either side of where it was found.
            let exact = tol::ULPS * (1.0 + found.abs());
            assert_close!(near.reach.from[0], found - TAU, exact, "{case}: {near:?}");
            assert_close!(near.reach.to[0], found + TAU, exact, "{case}: {near:?}");
            continue;
        }
        assert!(!near.turns_fully(), "{case}: {near:?}");
        let (lo, hi) =
            set.stretch_of(found, NEAR_LIMIT).unwrap_or_else(|| panic!("{case}: found {found} outside every stretch"));
        assert_close!(near.reach.from[0], lo, tol::LOCATED, "{case}: {near:?}");
        assert_close!(near.reach.to[0], hi, tol::LOCATED, "{case}: {near:?}");
        for (end, event) in [(near.reach.from[0], &near.reach.from_event), (near.reach.to[0], &near.reach.to_event)] {
            let event = event.as_ref().unwrap_or_else(|| panic!("{case}: an end without its event: {near:?}"));
            assert!(matches!(event.kind, kinloop::EventKind::LimitPosition), "{case}: {event:?}");
            assert_eq!(event.x, [end], "{case}: {near:?}");
        }
    }
    // Every class is met often enough that none passes for want of cases.
    assert!(counts.iter().all(|&n| n >= 20), "cases per class {counts:?}, {skipped} skipped");
    assert!(skipped <= 40, "{skipped} skipped");
}

/// A start a hair inside a limit position where the coupler and rocker stretch out (`4.2e-14`
/// rad of crank, its pivot ratio `1.1e-6`, just above the `1e-6` a sweep starts from): no step
/// the sweep takes is small enough to leave it on one branch. Its sweep is a singular start
/// (it was a branch the sweep "cannot stay on", which `assembly_near` passed on as its error),
/// and the search passes over it to the next sample, whose stretch ends at the limit.
#[test]
fn a_start_nearer_a_limit_than_the_smallest_step_is_passed_over() {
    for scale in [1e-6, 1.0, 1e6] {
        let m = FourBar {
            a: 2.0975839019901823 * scale,
            b: 0.6815279533920442 * scale,
            c: 1.177706737236556 * scale,
            d: 2.7106671235652855 * scale,
        };
        let lim = four_bar_limit(m.a, m.d, m.b + m.c);
        for inside in [4.2e-14, 5.6e-14] {
            let at = lim - inside;
            let q = m.position(at, &m.guess(at)).expect("it assembles a hair inside").0;
            let stopped = m.sweep(at, at - 0.1, 3, &q).unwrap().find_map(Result::err);
            assert!(matches!(stopped, Some(Error::SingularStart { .. })), "{scale} {inside}: {stopped:?}");
            let near = assembly_near(&m, [at], ASSEMBLY_SAMPLES).unwrap().expect("it assembles");
            assert!(near.found[0] < at, "{scale} {inside}: {near:?}");
            assert_close!(near.reach.to[0], lim, tol::LOCATED, "{scale} {inside}: {near:?}");
        }
    }
}
