//! Sweeps: branch safety, limit positions and singular crossings located precisely, assembly
//! modes, tables.

use kinloop::{AtSingular, Error, EventKind, NewtonConfig, Quantity, SweepConfig, SweepStop};
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::{FourBar, FourBarUnknowns};
use std::f64::consts::{PI, TAU};

use crate::support::{four_bar_joint, four_bar_limit, tol};

/// The side of the diagonal B -> D on which the four-bar's joint C = `(cx, cy)` lies at crank
/// angle `phi` (+1 left, -1 right, as [`four_bar_joint`] takes it): its assembly mode, from the
/// positions alone.
fn joint_side(m: &FourBar, phi: f64, cx: f64, cy: f64) -> f64 {
    let (bx, by) = (m.a * phi.cos(), m.a * phi.sin());
    ((m.d - bx) * (cy - by) - (0.0 - by) * (cx - bx)).signum()
}

/// The crank angles where coupler and rocker are collinear: `|BD| = b + c` or `|b - c|`.
pub(crate) fn limit_angles(m: &FourBar) -> Vec<f64> {
    [m.b + m.c, (m.b - m.c).abs()].into_iter().map(|r| four_bar_limit(m.a, m.d, r)).filter(|x| !x.is_nan()).collect()
}

#[test]
fn non_grashof_four_bar_stops_at_its_limit_position() {
    // s + l = 2 + 4 > p + q = 2.5 + 3: the input crank cannot turn fully.
    let m = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    let lim = limit_angles(&m);
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let mut sweep = m.sweep(0.0, PI, 181, &g).unwrap();
    let mut last = 0.0;
    let mut stop = None;
    for s in &mut sweep {
        match s {
            Ok(s) => last = s.input.phi,
            Err(e) => stop = Some(e),
        }
    }
    let ev = &sweep.events()[0];
    assert_eq!(ev.kind, EventKind::LimitPosition);
    assert!(matches!(stop, Some(Error::SweepStopped { kind: EventKind::LimitPosition, .. })), "{stop:?}");
    let expected = lim.iter().copied().find(|l| *l > 0.0 && *l < PI).unwrap();
    assert_close!(ev.x[0], expected, tol::LOCATED, "limit at {} vs law of cosines {expected}", ev.x[0]);
    assert!(last < expected && last > expected - PI / 180.0 - 1e-12);
    // At the limit position, coupler and rocker are collinear (extended): gamma = beta.
    let (beta, gamma) = (ev.q[0], ev.q[1]);
    assert!(((gamma - beta).sin()).abs() < 1e-6, "beta {beta} gamma {gamma}");
    // The error message names the input value, and what goes on from there: a trace.
    let msg = stop.unwrap().to_string();
    assert!(msg.contains("limit position") && msg.contains("phi = 1.37"), "{msg}");
    assert!(
        msg.contains("cannot go on past a limit position on this branch; `trace_curve` follows the curve"),
        "{msg}"
    );
}

#[test]
fn reachable_range_of_a_non_grashof_crank() {
    let m = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    let lim = limit_angles(&m)[0];
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let r = m.reachable(0.0, PI, &g, 91).unwrap();
    let (lo, hi) = (r.from.phi, r.to.phi);
    assert_close!(hi, lim, tol::LOCATED, "[{lo}, {hi}] vs +-{lim}");
    assert_close!(lo, -lim, tol::LOCATED, "[{lo}, {hi}] vs +-{lim}");
    // The ends are the located limit positions themselves.
    assert_eq!(r.to_event.expect("limit above").x[0], hi);
    assert_eq!(r.from_event.expect("limit below").x[0], lo);
    // The flat form answers in the same input values.
    let flat = kinloop::paths::reach::reachable(&m, [0.0], [PI], g.into(), 91).unwrap();
    assert_eq!((flat.from, flat.to), ([lo], [hi]));
}

/// `reachable`'s own arguments are checked under their names: a zero `delta` (no direction to
/// search), one that rounds away at `at`, and `at` or `delta` not finite, which its sweeps would
/// call their ranges' ends.
#[test]
fn reachable_names_a_zero_or_non_finite_delta_and_at() {
    let m = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let zero = m.reachable(0.0, 0.0, &g, 5).unwrap_err();
    assert!(matches!(&zero, Error::InvalidArgument(s) if s.contains("`delta` is zero")), "{zero}");
    // At 1e6 doubles are 1.16e-10 apart: a `delta` of 1e-11 moves neither end.
    let tiny = m.reachable(1e6, 1e-11, &g, 5).unwrap_err();
    assert!(
        matches!(&tiny, Error::InvalidArgument(s) if s.starts_with("reachable: `at - delta` rounds to `at`")),
        "{tiny}"
    );
    let at = m.reachable(f64::NAN, 1.0, &g, 5).unwrap_err();
    assert!(matches!(&at, Error::NonFinite { what: Quantity::Input, name, .. } if name == "phi"), "{at}");
    let delta = m.reachable(0.0, f64::INFINITY, &g, 5).unwrap_err();
    assert!(
        matches!(&delta, Error::NonFinite { what: Quantity::Range, name, .. } if name == "delta of phi"),
        "{delta}"
    );
    // Both finite, `at + delta` beyond the largest double: named as `delta`'s, not as a range
    // infinitely many turns long.
    let over = m.reachable(1e308, 1e308, &g, 5).unwrap_err();
    assert!(
        matches!(&over, Error::InvalidArgument(s) if s.starts_with("reachable: `at + delta` of phi overflows")),
        "{over}"
    );
    let over = m.reachable(-1e308, 1e308, &g, 5).unwrap_err();
    assert!(matches!(&over, Error::InvalidArgument(s) if s.contains("`at - delta` of phi overflows")), "{over}");
}

#[test]
fn near_change_point_four_bar_keeps_its_branch_over_ten_turns() {
    // s + l = 1 + 3 = 4 is just below p + q = 2 + 2.001: a crank-rocker that passes within
    // about sqrt(1e-3) of the other assembly mode twice per turn.
    let m = FourBar { a: 1.0, b: 3.0, c: 2.0, d: 2.001 };
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    // Which intersection kinloop assembled: at phi = 0 the two are mirror images in the x axis.
    let side = {
        let (cx, cy) = (m.a + m.b * g.beta.cos(), m.b * g.beta.sin());
        let (px, py) = four_bar_joint(m.a, m.b, m.c, m.d, 0.0, 1.0).unwrap();
        assert_close!(px, cx, 1e-9, "({cx}, {cy}) vs ({px}, +-{py})");
        assert_close!(py.abs(), cy.abs(), 1e-9, "({cx}, {cy}) vs ({px}, +-{py})");
        py.signum() * cy.signum()
    };
    let sweep = m.sweep(0.0, 20.0 * PI, 7201, &g).unwrap();
    let mut first = None;
    let mut last = None;
    for s in sweep {
        let s = s.unwrap();
        let (cx, cy) = four_bar_joint(m.a, m.b, m.c, m.d, s.input.phi, side).unwrap();
        assert_close!(s.out.pc.x, cx, 1e-9, "branch jump at {}", s.input.phi);
        assert_close!(s.out.pc.y, cy, 1e-9, "branch jump at {}", s.input.phi);
        first.get_or_insert(s.q);
        last = Some(s.q);
    }
    let (f, l) = (first.unwrap(), last.unwrap());
    assert_close!(f.beta, l.beta, 1e-9, "10 turns return to the start");
    assert_close!(f.gamma, l.gamma, 1e-9, "10 turns return to the start");
}

#[test]
fn change_point_crossing_is_located_and_never_silent() {
    // s + l = p + q exactly: at phi = 0 (mod 2 pi) all links are collinear (|BD| = d - a =
    // b - c) and the two assembly modes meet; the determinant changes sign there.
    let m = FourBar { a: 1.0, b: 3.0, c: 2.0, d: 2.0 };
    let g = m.position(0.5, &FourBarUnknowns { beta: 0.6, gamma: 1.6 }).unwrap().0;
    let mut sweep = m.sweep(0.5, 7.0, 66, &g).unwrap();
    let stop = sweep.by_ref().find_map(|s| s.err());
    assert!(matches!(stop, Some(Error::SweepStopped { kind: EventKind::SingularCrossing, .. })), "{stop:?}");
    // The message says what goes on from there: the smooth continuation when told to take it,
    // a trace, or, where two modes only pass close, a lower `singular_pivot`.
    let msg = stop.unwrap().to_string();
    for remedy in
        ["`AtSingular::Continue` (`SweepConfig::with_at_singular`)", "`trace_curve`", "`SweepConfig::singular_pivot`"]
    {
        assert!(msg.contains(remedy), "{remedy}: {msg}");
    }
    let ev = &sweep.events()[0];
    assert_close!(ev.x[0], 2.0 * PI, tol::LOCATED, "crossing at {}", ev.x[0]);

    // Configured to continue, the sweep passes the change point and records it.
    let cfg = SweepConfig::default().with_at_singular(AtSingular::Continue);
    let mut sweep = m.sweep(0.5, 7.0, 66, &g).unwrap().with_config(cfg);
    let all: Vec<_> = sweep.by_ref().collect::<Result<_, _>>().unwrap();
    assert_eq!(all.len(), 66);
    assert_eq!(sweep.events().len(), 1);
    // The smooth continuation through the change point changes the assembly mode: C lies on
    // the other side of the diagonal B -> D (by the positions, as a designer would see it), and
    // the state's determinant signs say so too.
    let side = |s: &kinloop_fixtures::FourBarState| joint_side(&m, s.input.phi, s.out.pc.x, s.out.pc.y);
    assert_eq!(side(&all[0]), -side(&all[65]));
    assert_ne!(all[0].health.det_signs, all[65].health.det_signs);
    for s in &all {
        assert!(m.residual(s.input, &s.q).iter().all(|r| r.abs() < 1e-10));
    }
}

#[test]
fn a_change_point_within_the_rounding_is_never_located_outside_the_sweep() {
    // a + d = b + c + eps with eps = -1e-14 (d = 4.5 - 1e-14): the two assembly modes pass
    // within about 1e-7 rad of each other at phi = pi, closer than the sweep can tell apart
    // (its pivot test). The diagnosis of the failed step once located a crossing radians away,
    // outside the swept range (at -1.79, -0.80 or 11.44 rad, depending on the samples). The
    // sweep stops at phi = pi: at the crossing, located there, or with the branch error that
    // says the branch cannot be pinned so close to a singular position.
    let (a, b, c) = (1.0, 3.0, 2.5);
    let m = FourBar { a, b, c, d: b + c - a - 1e-14 };
    let g = m.position(0.5, &m.guess(0.5)).unwrap().0;
    for samples in [2, 3, 5, 19, 37, 181, 2001] {
        let r = m.sweep(0.5, 0.5 + 2.0 * PI, samples, &g).unwrap().run();
        let at: Vec<f64> = r.events.iter().map(|e| e.x[0]).collect();
        assert!(r.events.len() <= 1, "{samples} samples: {at:?}");
        for e in &r.events {
            assert_eq!(e.kind, EventKind::SingularCrossing, "{samples} samples");
            assert_close!(e.x[0], PI, tol::LOCATED, "{samples} samples: the crossing at {}", e.x[0]);
        }
        match &r.stop {
            SweepStop::SingularCrossing(e) => assert_close!(e.x[0], PI, tol::LOCATED, "{samples} samples"),
            SweepStop::Failed(Error::Branch { at, .. } | Error::NearSingular { at, .. }) => {
                // Where the pivot falls below its threshold, about 1e-6 rad before pi.
                assert_close!(at.inputs[0].1, PI, 1e-5, "{samples} samples: {:?}", r.stop)
            }
            stop => panic!("{samples} samples: {stop:?}"),
        }
    }
}

#[test]
fn sweep_table_has_named_columns() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let table = m.sweep(0.0, 2.0 * PI, 73, &g).unwrap().table().unwrap();
    assert_eq!(table.rows.len(), 73);
    let beta = table.column("beta").unwrap();
    let dbeta = table.column("d(beta)/d(phi)").unwrap();
    let d2 = table.column("d2(pc.y)/d(phi)^2").unwrap();
    assert_eq!(beta.len(), 73);
    assert!(dbeta.iter().chain(&d2).all(|v| v.is_finite()));
    assert_close!(table.column("phi").unwrap()[72], 2.0 * PI, 1e-15);
    // The typed columns name the same columns as the strings.
    assert_eq!(table.column(FourBar::COL.beta), Some(beta));
    assert_eq!(table.column(FourBar::COL.pc.y), table.column("pc.y"));
    assert_eq!(table.unit(FourBar::COL.phi), Some("rad"));
    let mut csv = Vec::new();
    table.write_csv(&mut csv).unwrap();
    let text = String::from_utf8(csv).unwrap();
    // Units inferred by the macro: the input and the link angles in radians.
    assert!(text.starts_with("phi [rad],beta [rad],gamma [rad],d(beta)/d(phi) [rad/rad],"), "{text:.80}");
    assert_eq!(text.lines().count(), 74);
}

#[test]
fn assembly_modes_of_a_four_bar_are_elbow_up_and_down() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    let modes = m.assembly_modes(0.7).unwrap();
    assert_eq!(modes.len(), 2, "{modes:?}");
    let up = modes.iter().find(|s| s.out.pc.y > 0.0).expect("elbow up");
    let down = modes.iter().find(|s| s.out.pc.y < 0.0).expect("elbow down");
    // The two intersections of the circles (B, b) and (D, c), one on each side of B -> D.
    for mode in [up, down] {
        let side = joint_side(&m, 0.7, mode.out.pc.x, mode.out.pc.y);
        let (cx, cy) = four_bar_joint(m.a, m.b, m.c, m.d, 0.7, side).unwrap();
        assert_close!(mode.out.pc.x, cx, 1e-10);
        assert_close!(mode.out.pc.y, cy, 1e-10);
    }
    assert_eq!(joint_side(&m, 0.7, up.out.pc.x, up.out.pc.y), -joint_side(&m, 0.7, down.out.pc.x, down.out.pc.y));
    assert_ne!(up.health.det_signs, down.health.det_signs);
    // A sweep started from either mode stays in it: C on the same side of B -> D at every
    // sample, where the construction puts it (a crank-rocker never folds: the modes never meet).
    for mode in [up, down] {
        let side = joint_side(&m, 0.7, mode.out.pc.x, mode.out.pc.y);
        for s in m.sweep(0.7, 0.7 + 2.0 * PI, 37, &mode.q).unwrap() {
            let s = s.unwrap();
            let (cx, cy) = four_bar_joint(m.a, m.b, m.c, m.d, s.input.phi, side).unwrap();
            assert_close!(s.out.pc.x, cx, 1e-10, "at {}", s.input.phi);
            assert_close!(s.out.pc.y, cy, 1e-10, "at {}", s.input.phi);
            assert_eq!(s.health.det_signs, mode.health.det_signs);
        }
    }
}

/// At a limit position the two modes meet in a singular position: the modes are the solve's
/// `Singular` error there, not the empty list of inputs where the links cannot close. Beside it
/// (inside the range) both modes are found; beyond it, none.
#[test]
fn assembly_modes_at_a_limit_position_are_singular_not_empty() {
    // A double rocker: the crank cannot pass phi where |BD| = b + c.
    let m = FourBar { a: 2.0, b: 1.0, c: 1.5, d: 3.0 };
    let (a, b, c, d) = (m.a, m.b, m.c, m.d);
    let limit = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
    // The input within a few ulps of the limit where the point solve finds the position
    // singular (rounding decides which of the neighbours reach it).
    let at = (-4..=4)
        .map(|k: i64| f64::from_bits((limit.to_bits() as i64 + k) as u64))
        .find(|&x| matches!(m.kinematics(x, &m.guess(x)), Err(Error::Singular { .. })))
        .expect("a singular position within 4 ulps of the limit");
    let e = m.assembly_modes(at);
    assert!(matches!(e, Err(Error::Singular { .. })), "{e:?}");
    assert_eq!(m.assembly_modes(limit - 1e-3).unwrap().len(), 2);
    assert!(m.assembly_modes(limit + 1e-3).unwrap().is_empty());
}

/// Each mode's angles are on the declared guess's turn, within half a turn of it: the rhombic
/// drive's four modes (each rod to either side) came back with the displacer rod's angle a turn
/// below the guess's in some (-3.32 where the same angle is 2.97), from starts a turn away.
/// The positions are the closed forms', and each mode solves again from itself.
#[test]
fn assembly_modes_give_their_angles_on_the_guess_s_turn() {
    let m = kinloop_fixtures::RhombicDrive::default();
    let g = m.guess(0.3);
    let modes = m.assembly_modes(0.3).unwrap();
    assert_eq!(modes.len(), 4);
    for mode in &modes {
        for (q, g) in [(mode.q.phi2, g.phi2), (mode.q.phi4, g.phi4)] {
            assert!((q - g).abs() <= PI, "{:?} against the guess {g:?}", mode.q);
        }
        let again = m.kinematics(0.3, &mode.q).unwrap();
        assert_eq!((again.q.phi2, again.q.phi4), (mode.q.phi2, mode.q.phi4));
    }
}

/// An input or a parameter not finite is an error naming it: every start failed on it, and the
/// modes came back an empty list, as where the links cannot close.
#[test]
fn assembly_modes_at_values_not_finite_are_errors() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let e = m.assembly_modes(x);
        assert!(matches!(&e, Err(Error::NonFinite { what: Quantity::Input, name, .. }) if name == "phi"), "{x}: {e:?}");
    }
    let e = FourBar { c: f64::NAN, ..m }.assembly_modes(0.7);
    assert!(matches!(&e, Err(Error::NonFinite { what: Quantity::Parameter, name, .. }) if name == "c"), "{e:?}");
    let e = kinloop::paths::modes::assembly_modes(&m, &[0.7], 8, &NewtonConfig::default().with_residual_tol(-1.0));
    assert!(matches!(&e, Err(Error::InvalidArgument(_))), "{e:?}");
    // More starts than an analysis takes: refused before the first (u32::MAX ran for minutes).
    for starts in [kinloop::analysis::MAX_SAMPLES + 1, u32::MAX as usize, usize::MAX] {
        let e = kinloop::paths::modes::assembly_modes(&m, &[0.7], starts, &NewtonConfig::default());
        assert!(matches!(&e, Err(Error::InvalidArgument(s)) if s.contains("starts")), "{starts}: {e:?}");
    }
    // Where the links cannot close there is no mode, and no error.
    let far = FourBar { a: 1.0, b: 1.0, c: 1.0, d: 9.0 };
    assert_eq!(far.assembly_modes(0.0).unwrap().len(), 0);
}

#[test]
fn bad_sweep_arguments_are_errors() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    let g = m.guess(0.0);
    assert!(matches!(m.sweep(0.0, 1.0, 0, &g), Err(Error::InvalidArgument(_))));
    assert!(matches!(m.sweep(0.0, 0.0, 5, &g), Err(Error::InvalidArgument(_))));
    assert!(matches!(m.sweep(f64::NAN, 1.0, 5, &g), Err(Error::NonFinite { .. })));
    // A start that cannot assemble is reported at the first sample.
    let far = FourBar { a: 1.0, b: 1.0, c: 1.0, d: 9.0 };
    let first = far.sweep(0.0, 1.0, 3, &g).unwrap().next().unwrap();
    assert!(matches!(first, Err(Error::NoAssembly { .. })), "{first:?}");
}

/// A sweep of more intervals than an analysis holds is refused when it is made: `usize::MAX`
/// samples were accepted, and `run` or `table` on such a sweep stepped without end, keeping
/// every state. The largest count allowed is still a lazy sweep one can take from.
#[test]
fn a_sweep_of_more_samples_than_an_analysis_holds_is_refused() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.0 };
    let g = m.guess(0.0);
    let most = kinloop::analysis::MAX_SAMPLES + 1;
    for samples in [most + 1, u32::MAX as usize, usize::MAX] {
        let e = m.sweep(0.0, 1.0, samples, &g).map(|_| ());
        assert!(matches!(&e, Err(Error::InvalidArgument(s)) if s.contains("MAX_SAMPLES")), "{samples}: {e:?}");
    }
    let first: Vec<_> = m.sweep(0.0, 1.0, most, &g).unwrap().take(2).collect();
    assert!(first.len() == 2 && first.iter().all(Result::is_ok), "{first:?}");
}

/// A traced curve closes where it comes back through its start, not where it comes near it. A
/// gear-lever drive whose gear ratio `u` is not whole does not repeat its motion after a turn of
/// the crank (the planet turns by `(1 - u) 2 pi` about its pin, so the pin is elsewhere), and
/// with steps of half a radian and more it was reported closed, the trace cut short, where it
/// came within three quarters of a step of its start (59 of 60 random such drives at
/// `ds = 1`); the whole ratio of the paper repeats after a turn and closes at every step.
#[test]
fn a_traced_curve_closes_where_it_passes_its_start_not_where_it_comes_near_it() {
    let from = -PI / 3.0;
    for ds in [0.01, 0.5, 1.0] {
        let cfg = kinloop::TraceConfig::default().with_ds(ds);
        let whole = GearLever::default();
        let t = whole.trace_curve(from, from + 2.0 * TAU, &whole.guess(from), &cfg).unwrap();
        assert!(t.closed && !t.truncated, "u = {}, ds = {ds}: {} points", whole.u, t.points.len());
        let fractional = GearLever { u: 2.7, ..GearLever::default() };
        let t = fractional.trace_curve(from, from + 2.0 * TAU, &fractional.guess(from), &cfg).unwrap();
        // It follows its motion over both turns, to the end of the segment.
        let last = t.points.last().unwrap().x[0];
        assert!(
            !t.closed && !t.truncated && last > from + 2.0 * TAU - 1.0,
            "u = 2.7, ds = {ds}: closed {}, to {last}",
            t.closed
        );
    }
}

#[test]
fn arclength_traces_the_whole_closed_curve_of_a_non_grashof_four_bar() {
    let m = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    let lim = limit_angles(&m)[0];
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let t = m.trace_curve(0.0, PI, &g, &kinloop::TraceConfig::default().with_ds(0.02)).unwrap();
    assert!(t.closed, "the curve closes on itself");
    assert_eq!(t.folds.len(), 2, "{:?}", t.folds);
    let mut at: Vec<f64> = t.folds.iter().map(|f| f.x[0]).collect();
    at.sort_by(f64::total_cmp);
    assert_close!(at[0], -lim, tol::LOCATED, "{at:?} vs +-{lim}");
    assert_close!(at[1], lim, tol::LOCATED, "{at:?} vs +-{lim}");
    // Both assembly modes are on the one closed curve: the input reverses at each fold.
    assert!(t.points.iter().any(|p| p.input_rate < 0.0) && t.points.iter().any(|p| p.input_rate > 0.0));
    for p in &t.points {
        let r = m.residual(p.x[0], &p.q.into());
        assert!(r.iter().all(|v| v.abs() < 1e-10));
    }
}

/// A trace started exactly at a limit position (the input a sweep that stopped there reports)
/// starts there: the velocity analogs do not exist, but the curve's tangent does. It lists the
/// start as a limit position once, the other one where the law of cosines puts it, and closes.
#[test]
fn a_trace_starts_at_a_limit_position_where_a_sweep_stopped() {
    let m = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    let lim = limit_angles(&m)[0];
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let mut sweep = m.sweep(0.0, PI, 181, &g).unwrap();
    let stop = sweep.by_ref().find_map(Result::err);
    assert!(matches!(stop, Some(Error::SweepStopped { kind: EventKind::LimitPosition, .. })), "{stop:?}");
    let event = sweep.events()[0].clone();
    let at = event.x[0];
    let q: [f64; 2] = event.q[..].try_into().unwrap();
    let q = FourBarUnknowns::from(q);
    // The analogs do not exist there: a point solve fails as singular.
    assert!(matches!(m.kinematics(at, &q), Err(Error::Singular { .. })));
    // Towards either side: the segment from `at - (to - at)` to `to` holds the whole curve.
    for to in [-PI, 3.0 * at + 0.5] {
        let cfg = kinloop::TraceConfig::default().with_ds(0.02);
        let t = m.trace_curve(at, to, &q, &cfg).unwrap();
        assert!(t.closed, "to {to}: the curve closes on itself");
        let mut folds: Vec<f64> = t.folds.iter().map(|f| f.x[0]).collect();
        assert_eq!(folds.len(), 2, "to {to}: {folds:?}");
        assert_eq!(folds[0], at, "to {to}: the start is listed first");
        folds.sort_by(f64::total_cmp);
        assert_close!(folds[0], -lim, tol::LOCATED, "to {to}: {folds:?} vs +-{lim}");
        assert_close!(folds[1], lim, tol::LOCATED, "to {to}: {folds:?} vs +-{lim}");
        for p in &t.points {
            let r = m.residual(p.x[0], &p.q.into());
            assert!(r.iter().all(|v| v.abs() < 1e-10), "to {to}: {r:?}");
        }
    }
}

/// A slider-crank whose crank rocks (`r > l + |e|`): at its limit position the rod's closed
/// form meets `asin(1)` exactly, the pivot ratio is 0 and no analog exists even unchecked; the
/// trace starts there all the same, from the positions alone. Its curve (both rod angles, joined
/// at the limits `r sin phi - e = +-l`) closes, with the start listed first.
#[test]
fn a_trace_starts_at_a_slider_cranks_limit_where_the_pivot_is_zero() {
    let m = kinloop_fixtures::SliderCrank { r: 2.0, l: 1.5, e: 0.3 };
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let mut sweep = m.sweep(0.0, 3.0, 40, &g).unwrap();
    assert!(matches!(sweep.by_ref().find_map(Result::err), Some(Error::SweepStopped { .. })));
    let event = sweep.events()[0].clone();
    let (at, q) = (event.x[0], <[f64; 2]>::try_from(&event.q[..]).unwrap());
    let upper = ((m.e + m.l) / m.r).asin();
    let lower = ((m.e - m.l) / m.r).asin();
    assert_close!(at, upper, tol::LOCATED);
    let singular = m.kinematics_with(at, &q.into(), &NewtonConfig::default().with_singular_tol(0.0));
    assert!(singular.is_err(), "{singular:?}");
    let t = m.trace_curve(at, -3.0, &q.into(), &kinloop::TraceConfig::default().with_ds(0.02)).unwrap();
    assert!(t.closed);
    let folds: Vec<f64> = t.folds.iter().map(|f| f.x[0]).collect();
    assert_eq!(folds.len(), 2, "{folds:?}");
    assert_eq!(folds[0], at);
    assert_close!(folds[1], lower, tol::LOCATED, "{folds:?}");
    for p in &t.points {
        assert!(m.residual(p.x[0], &p.q.into()).iter().all(|v| v.abs() < 1e-10), "{p:?}");
    }
}

/// The four-bar solved by Newton's method reaches its limit position only linearly: a point
/// solve there fails as singular even unchecked, its positions known to about the square root of
/// the rounding. The trace starts all the same, at the limit position located from a regular
/// point beside it (the input it names is the closed form's to the rounding), and lists it
/// first; at inputs a few ulps to either side of it too.
#[test]
fn a_trace_starts_at_a_newton_blocks_limit_position() {
    use crate::sweep_api::NewtonFourBar;
    let (a, b, c, d) = (3.0, 2.0, 2.5, 4.0);
    let m = NewtonFourBar { a, b, c, d };
    let lim = limit_angles(&FourBar { a, b, c, d })[0];
    let g = m.guess(lim);
    let unchecked = NewtonConfig::default().with_singular_tol(0.0);
    assert!(matches!(m.position_with(lim, &g, &unchecked), Err(Error::Singular { .. })));
    for at in [lim, lim.next_up().next_up(), lim.next_down().next_down()] {
        let t = m.trace_curve(at, -PI, &g, &kinloop::TraceConfig::default().with_ds(0.02)).unwrap();
        assert!(t.closed, "from {at}");
        let folds: Vec<f64> = t.folds.iter().map(|f| f.x[0]).collect();
        assert_eq!(folds.len(), 2, "from {at}: {folds:?}");
        assert_close!(folds[0], lim, tol::LOCATED, "from {at}: {folds:?}");
        assert_close!(folds[1], -lim, tol::LOCATED, "from {at}: {folds:?}");
        assert_eq!(t.points[0].x[0], folds[0], "from {at}: the trace starts at the limit position");
        for p in &t.points {
            assert!(m.residual(p.x[0], &p.q.into()).iter().all(|v| v.abs() < 1e-10), "{p:?}");
        }
    }
}

/// A sweep from a limit position (the end of a reachable range): its first state solves, with
/// the rounding's analogs, but no step in the input leaves it on one branch (both assembly
/// modes meet there). The error says so and what to do, at the start; it said the sweep could
/// not stay on its branch, at an input a few ulps on.
#[test]
fn a_sweep_from_a_limit_position_says_it_starts_at_one() {
    let m = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    let g = m.position(0.0, &m.guess(0.0)).unwrap().0;
    let reach = m.reachable(0.0, PI, &g, 91).unwrap();
    let at = reach.to.phi;
    let q = FourBarUnknowns::from(<[f64; 2]>::try_from(&reach.to_event.as_ref().unwrap().q[..]).unwrap());
    let mut sweep = m.sweep(at, 0.0, 5, &q).unwrap();
    let e = sweep.by_ref().find_map(Result::err).expect("an error");
    let message = e.to_string();
    assert!(
        matches!(e, Error::SingularStart { pivot_ratio, singular_pivot, .. } if pivot_ratio < singular_pivot),
        "{e:?}"
    );
    assert!(message.starts_with("the sweep starts at a singular position"), "{message}");
    assert!(message.contains(&format!("phi = {at}")) && message.contains("trace_curve"), "{message}");
}

/// The pivot ratio a singular start reports is the one `SweepConfig::singular_pivot` is
/// compared with, `Health::min_pivot`'s (of the analogs' factorisations), also where the first
/// state's point solve finds it singular: there the analogs at the positions solved alone, the
/// ratio of the block whose factorisation fails (`kinematics_at`'s `Singular`). The point
/// solve's own measure was reported and compared with `singular_pivot`: at the slider-crank's
/// limit position where its sweep stopped, its closed form's 0, "below `singular_pivot`", with
/// every `singular_pivot`.
#[test]
fn a_singular_start_reports_the_pivot_ratio_singular_pivot_is_compared_with() {
    use kinloop::Named;
    let slider = kinloop_fixtures::SliderCrank { r: 2.0, l: 1.5, e: 0.3 };
    let g = slider.position(0.0, &slider.guess(0.0)).unwrap().0;
    let mut sweep = slider.sweep(0.0, 3.0, 91, &g).unwrap();
    assert!(matches!(sweep.by_ref().find_map(Result::err), Some(Error::SweepStopped { .. })));
    let event = sweep.events()[0].clone();
    let (at, q) = (event.x[0], <[f64; 2]>::try_from(&event.q[..]).unwrap().into());
    // The point solve finds the start singular; the analogs' ratio at its positions is had alone.
    let point = slider.kinematics(at, &q);
    assert!(matches!(point, Err(Error::Singular { .. })), "{point:?}");
    let solved = slider.position(at, &q).unwrap().0;
    let analogs = match slider.kinematics_at(at, &solved) {
        Ok(k) => k.health.min_pivot,
        Err(Error::Singular { pivot_ratio, .. }) => pivot_ratio,
        Err(e) => panic!("{e:?}"),
    };
    // With the default `singular_pivot` and with one below every ratio: the same measure, and
    // the message says it is below `singular_pivot` only where it is.
    for singular_pivot in [SweepConfig::default().singular_pivot, 0.0] {
        let cfg = SweepConfig::default().with_singular_pivot(singular_pivot);
        let e = slider.with_config(cfg).unwrap().sweep(at, 0.0, 5, &q).unwrap().find_map(Result::err);
        let Some(Error::SingularStart { pivot_ratio, .. }) = e else { panic!("{e:?}") };
        assert_eq!(pivot_ratio, analogs, "singular_pivot {singular_pivot}: {e:?}");
        let message = e.unwrap().to_string();
        let below = message.contains("below `SweepConfig::singular_pivot`");
        assert_eq!(below, pivot_ratio < singular_pivot, "singular_pivot {singular_pivot}: {message}");
    }
}

/// A sweep from the limit position where a sweep stopped (its event's input and positions)
/// says it starts at one, with what to do instead, as from the end of a reachable range: also
/// where the first state does not solve even with the rounding's analogs (the slider-crank's
/// pivot ratio is 0, below `NewtonConfig::singular_tol`), where the error was the point solve's
/// `Singular`, which does not say that no sweep leaves the start on one branch.
#[test]
fn a_sweep_from_where_a_sweep_stopped_says_it_starts_at_a_limit_position() {
    let slider = kinloop_fixtures::SliderCrank { r: 2.0, l: 1.5, e: 0.3 };
    let four_bar = FourBar { a: 3.0, b: 2.0, c: 2.5, d: 4.0 };
    // Each mechanism swept until it stops, then from its event.
    let mut errors = Vec::new();
    let g = slider.position(0.0, &slider.guess(0.0)).unwrap().0;
    let mut sweep = slider.sweep(0.0, 3.0, 91, &g).unwrap();
    assert!(matches!(sweep.by_ref().find_map(Result::err), Some(Error::SweepStopped { .. })));
    let event = sweep.events()[0].clone();
    let q = <[f64; 2]>::try_from(&event.q[..]).unwrap().into();
    errors.push(("slider-crank", event.x[0], slider.sweep(event.x[0], 0.0, 5, &q).unwrap().find_map(Result::err)));
    let g = four_bar.position(0.0, &four_bar.guess(0.0)).unwrap().0;
    let mut sweep = four_bar.sweep(0.0, PI, 91, &g).unwrap();
    assert!(matches!(sweep.by_ref().find_map(Result::err), Some(Error::SweepStopped { .. })));
    let event = sweep.events()[0].clone();
    let q = FourBarUnknowns::from(<[f64; 2]>::try_from(&event.q[..]).unwrap());
    errors.push(("four-bar", event.x[0], four_bar.sweep(event.x[0], 0.0, 5, &q).unwrap().find_map(Result::err)));
    for (name, at, e) in errors {
        let e = e.expect("an error");
        let message = e.to_string();
        // The slider-crank's start does not solve (pivot ratio 0, the point solve's `Singular`);
        // the four-bar's solves with the rounding's analogs (below `singular_pivot` only).
        let bound = if name == "slider-crank" { NewtonConfig::default().singular_tol } else { 1e-6 };
        assert!(matches!(e, Error::SingularStart { pivot_ratio, .. } if pivot_ratio < bound), "{name}: {e:?}");
        assert!(message.contains(&format!("= {at}")) && message.contains("trace_curve"), "{name}: {message}");
    }
}
