//! Design-space scans: `scan` and `par_scan` over about 200 offset slider-cranks, among them
//! sets that cannot be assembled, sets whose crank cannot turn fully (a limit position) and a
//! set with a NaN parameter. Each successful set's extremes (folded over a turn with no table)
//! are checked against the closed forms, each failing set's error against its cause, and the
//! parallel results against the sequential ones bit for bit.
//!
//! The root package's dev-dependency on `kinloop-runtime` with its `rayon` feature makes
//! `par_scan` available to every `cargo test` (features unify), so these tests never compile it
//! out; `par_scan_runs_on_the_rayon_pool` also checks that the sets were computed on rayon's
//! worker threads, not on the calling one. A counting allocator shows that a scan allocates
//! nothing per set or per sample: only its result vector.

use kinloop::{Error, EventKind, Kin, ScanConfig, ScanStart, par_scan, scan};
use kinloop_fixtures::SliderCrank;
use kinloop_fixtures::strategies::{limited_slider_crank, sample, turning_slider_crank, unassemblable_slider_crank};
use std::collections::HashSet;
use std::f64::consts::{PI, TAU};
use std::sync::Mutex;
use std::thread::{self, ThreadId};

#[path = "support/counting_alloc.rs"]
mod counting_alloc;

use counting_alloc::allocations;

/// Samples per turn (every half degree).
const SAMPLES: usize = 721;
/// Sample spacing.
const H: f64 = TAU / (SAMPLES - 1) as f64;

/// Smallest and largest value of one unknown over a sweep. Besides the samples, each sample
/// whose velocity and acceleration analogs put a stationary point within half a spacing
/// contributes the extreme of its local Taylor parabola, `v - v'^2 / (2 v'')`: the extremes are
/// then accurate to `O(h^3)` instead of the samples' `O(h^2)`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Extremes {
    lo: f64,
    hi: f64,
}

impl Extremes {
    const EMPTY: Extremes = Extremes { lo: f64::INFINITY, hi: f64::NEG_INFINITY };

    fn add(self, v: f64, d1: f64, d2: f64) -> Extremes {
        let (mut lo, mut hi) = (self.lo.min(v), self.hi.max(v));
        if d2 != 0.0 && (d1 / d2).abs() <= 0.5 * H {
            let top = v - d1 * d1 / (2.0 * d2);
            if d2 < 0.0 {
                hi = hi.max(top);
            } else {
                lo = lo.min(top);
            }
        }
        Extremes { lo, hi }
    }
}

/// The fold's accumulator: extremes of `psi` and `x`, and the number of samples seen.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Acc {
    psi: Extremes,
    x: Extremes,
    samples: usize,
}

fn init(_: &SliderCrank) -> Acc {
    Acc { psi: Extremes::EMPTY, x: Extremes::EMPTY, samples: 0 }
}

fn fold(a: Acc, _: &SliderCrank, k: &Kin<2, 1, 0>) -> Acc {
    Acc {
        psi: a.psi.add(k.q[0], k.dq[0][0], k.d2q[0][0][0]),
        x: a.x.add(k.q[1], k.dq[1][0], k.d2q[1][0][0]),
        samples: a.samples + 1,
    }
}

/// What a design must give.
#[derive(Clone, Copy, Debug)]
enum Expect {
    /// A full turn (`r + |e| < l`).
    Turn,
    /// Cannot be assembled at `phi = 0` (`|e| > l`).
    NoAssembly,
    /// Assembles but stops at a limit position at this crank angle (`l - r < |e| < l`).
    Limit(f64),
    /// A NaN parameter.
    NonFinite,
}

/// `n` designs with what each must give: mostly full turns, every 23rd unassemblable, every
/// 29th stopping at a limit position, one with a NaN rod; drawn from the fixtures' strategies,
/// which stay clear of the boundaries between these cases.
fn designs(n: usize) -> (Vec<SliderCrank>, Vec<Expect>) {
    let (turning, unassemblable, limited) = (
        sample(turning_slider_crank(), n, 5),
        sample(unassemblable_slider_crank(), n, 6),
        sample(limited_slider_crank(), n, 7),
    );
    (0..n)
        .map(|i| {
            if i == 100 {
                (SliderCrank { r: 1.0, l: f64::NAN, e: 0.1 }, Expect::NonFinite)
            } else if i % 23 == 11 {
                (unassemblable[i], Expect::NoAssembly)
            } else if i % 29 == 17 {
                // |e| = l - 0.3 < l, and r + |e| > l: r sin(phi) - e reaches -sign(e) l first (the
                // other bound needs r >= l + |e| > r), where sin(phi) = -sign(e) 0.3 / r.
                let m = limited[i];
                let s = 0.3 / m.r;
                (m, Expect::Limit(if m.e > 0.0 { PI + s.asin() } else { s.asin() }))
            } else {
                (turning[i], Expect::Turn)
            }
        })
        .unzip()
}

/// The designs among the first `n` that turn fully.
fn turning_designs(n: usize) -> Vec<SliderCrank> {
    let (ms, ex) = designs(n);
    ms.into_iter().zip(ex).filter(|(_, e)| matches!(e, Expect::Turn)).map(|(m, _)| m).collect()
}

/// Closed forms of a full turn on the declared branch (`psi` near 0, the rod pointing from the
/// slider towards +x): `sin psi = (r sin phi - e) / l`, so `psi` spans
/// `asin((-r - e) / l) ..= asin((r - e) / l)`; the slider is farthest from the crank's centre
/// when crank and rod are stretched (`|OC| = l + r`) and nearest when folded (`|OC| = l - r`).
fn closed_form(m: &SliderCrank) -> Acc {
    let far = ((m.l + m.r).powi(2) - m.e * m.e).sqrt();
    let near = ((m.l - m.r).powi(2) - m.e * m.e).sqrt();
    Acc {
        psi: Extremes { lo: ((-m.r - m.e) / m.l).asin(), hi: ((m.r - m.e) / m.l).asin() },
        x: Extremes { lo: -far, hi: -near },
        samples: SAMPLES,
    }
}

/// Extremes from a sweep (Taylor-refined, see [`Extremes`]) against the closed forms. The
/// refinement's error is of order `|v'''| (h/2)^3`: at most 8e-9 over the whole range of the
/// turning strategy (3000 designs, from the closed forms; the samples alone are off by up to
/// 2.3e-5, so the tolerance also proves the analogs reach the fold). The extremes of `psi` lie
/// on samples (`phi = pi/2, 3pi/2`) and agree to rounding.
const TOL: f64 = 1e-7;

fn check_results(ms: &[SliderCrank], ex: &[Expect], results: &[Result<Acc, Error>]) {
    assert_eq!(results.len(), ms.len());
    let mut counts = [0; 4];
    for (i, ((m, e), r)) in ms.iter().zip(ex).zip(results).enumerate() {
        match (e, r) {
            (Expect::Turn, Ok(a)) => {
                counts[0] += 1;
                let want = closed_form(m);
                assert_eq!(a.samples, SAMPLES, "set {i}");
                let devs = [a.psi.lo - want.psi.lo, a.psi.hi - want.psi.hi, a.x.lo - want.x.lo, a.x.hi - want.x.hi];
                assert!(devs.iter().all(|d| d.abs() < TOL), "set {i} {m:?}: deviations {devs:?}");
                let stroke = a.x.hi - a.x.lo;
                let want_stroke = ((m.l + m.r).powi(2) - m.e * m.e).sqrt() - ((m.l - m.r).powi(2) - m.e * m.e).sqrt();
                assert!((stroke - want_stroke).abs() < 2.0 * TOL, "set {i}: stroke {stroke} vs {want_stroke}");
            }
            (Expect::NoAssembly, Err(Error::NoAssembly { at, .. })) => {
                counts[1] += 1;
                assert_eq!(at.inputs, [("phi".into(), 0.0)], "set {i}");
            }
            (Expect::Limit(limit), Err(Error::SweepStopped { kind: EventKind::LimitPosition, at })) => {
                counts[2] += 1;
                let phi = at.inputs[0].1;
                assert!((phi - limit).abs() < 1e-9, "set {i} {m:?}: limit at {phi}, law of sines {limit}");
            }
            (Expect::NonFinite, Err(Error::NonFinite { name, .. })) if name == "l" => counts[3] += 1,
            _ => panic!("set {i} {m:?}: expected {e:?}, got {r:?}"),
        }
    }
    // Every kind of slot is there.
    assert!(counts[0] > 150 && counts[1] >= 8 && counts[2] >= 6 && counts[3] == 1, "{counts:?}");
}

/// The results compared bit for bit (`==` would also equate `0.0` and `-0.0`).
fn bits(results: &[Result<Acc, Error>]) -> Vec<Result<([u64; 4], usize), String>> {
    results
        .iter()
        .map(|r| match r {
            Ok(a) => Ok(([a.psi.lo.to_bits(), a.psi.hi.to_bits(), a.x.lo.to_bits(), a.x.hi.to_bits()], a.samples)),
            Err(e) => Err(format!("{e:?}")),
        })
        .collect()
}

#[test]
fn scan_matches_closed_forms_and_par_scan_matches_scan_bitwise() {
    let (ms, ex) = designs(200);
    let spec = ScanConfig::new([0.0], [TAU], SAMPLES);
    let seq = scan(&ms, &spec, init, fold);
    check_results(&ms, &ex, &seq);
    let par = par_scan(&ms, &spec, init, fold);
    check_results(&ms, &ex, &par);
    // Bit for bit, errors by their full description (`==` would fail on the NaN set's error,
    // which carries the NaN).
    assert_eq!(bits(&par), bits(&seq));
}

#[test]
fn scan_allocates_only_its_result() {
    let turns = turning_designs(60);
    let spec = ScanConfig::new([0.0], [TAU], SAMPLES);
    let (results, n) = allocations(|| scan(&turns, &spec, init, fold));
    assert!(results.iter().all(|r| r.as_ref().is_ok_and(|a| a.samples == SAMPLES)));
    assert_eq!(n, 1, "{} sets of {SAMPLES} samples: {n} allocations", turns.len());
}

#[test]
fn par_scan_runs_on_the_rayon_pool() {
    let (ms, _) = designs(64);
    let spec = ScanConfig::new([0.0], [TAU], 37);
    let threads = Mutex::new(Vec::<ThreadId>::new());
    let init = |m: &SliderCrank| {
        threads.lock().unwrap().push(thread::current().id());
        init(m)
    };
    let here = thread::current().id();

    let seq = scan(&ms, &spec, init, fold);
    let seen = std::mem::take(&mut *threads.lock().unwrap());
    // `init` runs once per set that gets past `Sweep::new` (all of them here).
    assert_eq!(seen.len(), ms.len());
    assert!(seen.iter().all(|t| *t == here));

    let par = par_scan(&ms, &spec, init, fold);
    let seen = std::mem::take(&mut *threads.lock().unwrap());
    assert_eq!(seen.len(), ms.len());
    // The caller blocks while rayon's workers compute: no set ran on the calling thread.
    assert!(seen.iter().all(|t| *t != here), "par_scan ran a set on the calling thread");
    let distinct: HashSet<_> = seen.iter().collect();
    eprintln!(
        "par_scan: {} sets on {} rayon worker thread(s) ({} cores available)",
        ms.len(),
        distinct.len(),
        thread::available_parallelism().map_or(1, |n| n.get())
    );
    assert_eq!(bits(&par), bits(&seq));
}

#[test]
fn the_start_policy_picks_the_branch() {
    // The mirrored branch (psi near pi, the slider on the crank's +x side) from a computed guess
    // and from a fixed one: x spans the closed forms' mirror image.
    let turns = turning_designs(60);
    let with = ScanConfig::new([0.0], [TAU], SAMPLES).start(ScanStart::With(|m: &SliderCrank| [PI + m.e / m.l, m.l]));
    let fixed = ScanConfig::new([0.0], [TAU], SAMPLES).start(ScanStart::Guess([3.0, 1.0]));
    for spec in [with, fixed] {
        let seq = scan(&turns, &spec, init, fold);
        for (m, r) in turns.iter().zip(&seq) {
            let a = r.as_ref().unwrap();
            let want = closed_form(m);
            let (far, near) = (-want.x.lo, -want.x.hi);
            assert!((a.x.lo - near).abs() < TOL && (a.x.hi - far).abs() < TOL, "{m:?}: {a:?} {:?}", spec.start);
            // psi' = pi - psi: mirrored extremes.
            assert!((a.psi.lo - (PI - want.psi.hi)).abs() < TOL && (a.psi.hi - (PI - want.psi.lo)).abs() < TOL);
        }
        assert_eq!(bits(&par_scan(&turns, &spec, init, fold)), bits(&seq));
    }
}

#[test]
fn bad_arguments_fail_every_slot_without_panicking() {
    let (ms, _) = designs(5);
    assert!(scan(&ms[..0], &ScanConfig::new([0.0], [TAU], SAMPLES), init, fold).is_empty());
    assert!(par_scan(&ms[..0], &ScanConfig::new([0.0], [TAU], SAMPLES), init, fold).is_empty());
    // Among them: one sample of a range to another end (the end was ignored), and more samples
    // than an analysis takes (`usize::MAX` folded for years).
    let cases = [
        ScanConfig::new([0.0], [TAU], 0),
        ScanConfig::new([0.0], [0.0], 3),
        ScanConfig::new([f64::NAN], [TAU], 3),
        ScanConfig::new([0.0], [TAU], 1),
        ScanConfig::new([0.0], [TAU], kinloop::analysis::MAX_SAMPLES + 1),
        ScanConfig::new([0.0], [TAU], usize::MAX),
    ];
    for spec in cases {
        for results in [scan(&ms, &spec, init, fold), par_scan(&ms, &spec, init, fold)] {
            assert_eq!(results.len(), ms.len());
            assert!(
                results.iter().all(|r| matches!(r, Err(Error::InvalidArgument(_) | Error::NonFinite { .. }))),
                "{spec:?}: {results:?}"
            );
        }
    }
    // An end not finite is named as such, with one sample too (a NaN end differs from itself:
    // it was said to need 2 samples).
    for spec in [ScanConfig::new([f64::NAN], [f64::NAN], 1), ScanConfig::new([0.0], [f64::INFINITY], 1)] {
        for results in [scan(&ms, &spec, init, fold), par_scan(&ms, &spec, init, fold)] {
            assert!(results.iter().all(|r| matches!(r, Err(Error::NonFinite { .. }))), "{spec:?}: {results:?}");
        }
    }
    // One sample: the start position alone.
    let one = scan(&ms, &ScanConfig::new([0.5], [0.5], 1), init, fold);
    assert!(one.iter().all(|r| r.as_ref().unwrap().samples == 1));
}
