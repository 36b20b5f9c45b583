//! Every peer of the benchmarks against the reference before anything is timed: the rhombic
//! drive's peers against the published closed form, the class IV block's hand-written Newton
//! against kinloop and against finite differences of its own positions. (The benchmarks repeat
//! the check over the full 1,000,000-step turn in release mode; here a coarser turn keeps the
//! debug-mode test fast.) kinloop's own sweep is checked the same way, at the angles it samples.

use kinloop::Mechanism;
use kinloop_bench::class_four::{self, HandNewton};
use kinloop_bench::hand::{FOUR_BAR, FourBarClosed, GearLeverClosed, gear_lever};
use kinloop_bench::kinloop_variants::{Kinloop, KinloopNamed, check_kinloop_sweep};
use kinloop_bench::rhombic::{
    self, ClosedForm, ClosedFormLibmSum, DenseFiniteDifference, DenseHandJacobian, DenseNumDual, TwoLoopNewton,
};
use kinloop_bench::sweep::{DIFFERENCED, EXACT, Stepper, SweepCheck, WarmStart, check_sweep};

const STEPS: usize = 5_000;

fn check<S: Stepper<4>, R: Stepper<4>>(name: &str, s: &S, r: &R, guess0: [f64; 4], tol: [f64; 3]) -> [SweepCheck; 2] {
    WarmStart::ALL.map(|policy| {
        let c = check_sweep(s, r, STEPS, policy, guess0).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(c.max_dev.iter().zip(tol).all(|(d, t)| *d <= t), "{name} ({policy:?}): {c:?}");
        c
    })
}

/// kinloop's own sweep (its own Taylor predictor) against the reference at the same angles.
fn check_sweep_of<M: Mechanism<4, 1, 0>, R: Stepper<4>>(name: &str, m: &M, r: &R, guess0: [f64; 4]) {
    let c = check_kinloop_sweep(m, r, STEPS, guess0).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(c.max_dev.iter().zip(EXACT).all(|(d, t)| *d <= t), "{name}: {c:?}");
}

#[test]
fn rhombic_peers_match_the_closed_form() {
    let p = rhombic::PARAMS;
    let g = rhombic::initial_guess(&p);
    let closed = ClosedForm::new(&p);
    check("kinloop", &Kinloop::<_, 0>::new(p.kinloop()), &closed, g, EXACT);
    check("kinloop_named", &KinloopNamed::new(p.kinloop()), &closed, g, EXACT);
    check_sweep_of("kinloop_sweep", &p.kinloop(), &closed, g);
    let [taylor, previous] = check("two_loop_newton", &TwoLoopNewton { p }, &closed, g, EXACT);
    // The predictor leaves less to iterate than the previous position (at 1,000,000 steps per
    // turn it leaves nothing: see the benchmarks' checks).
    assert!(taylor.mean_iterations < previous.mean_iterations, "{taylor:?} {previous:?}");
    check("dense_hand_jacobian", &DenseHandJacobian { p }, &closed, g, EXACT);
    check("dense_num_dual", &DenseNumDual { p }, &closed, g, EXACT);
    check("dense_finite_difference", &DenseFiniteDifference { p }, &closed, g, DIFFERENCED);
    // The closed form as the paper writes it, `sin(phi1 + gamma)` from libm: the leaner
    // reference's angle addition (within about 1.5 ulp of the exact sum's values, libm's of the
    // rounded sum within its rounding, 4.4e-16 rad near 2 pi) gives the same positions and
    // analogs to a few units in the last place of the drive's lengths (about 3.5).
    check("closed_form_libm_sum", &ClosedFormLibmSum(closed), &closed, g, [4e-15, 1e-14, 1e-14]);
}

#[test]
fn class_four_hand_newton_matches_kinloop() {
    let p = class_four::PARAMS;
    let hand = HandNewton { p };
    let g = class_four::INITIAL_GUESS;
    check("kinloop", &Kinloop::<_, 0>::new(p.kinloop()), &hand, g, EXACT);
    check("kinloop_named", &KinloopNamed::new(p.kinloop()), &hand, g, EXACT);
    check_sweep_of("kinloop_sweep", &p.kinloop(), &hand, g);
}

#[test]
fn class_four_hand_analogs_are_derivatives_of_its_positions() {
    // Central differences of the hand-written solver's own positions and velocity analogs.
    let hand = HandNewton { p: class_four::PARAMS };
    let mut q = class_four::INITIAL_GUESS;
    for k in 0..72 {
        let phi = k as f64 * std::f64::consts::TAU / 72.0;
        let s = hand.step(phi, &q).unwrap();
        q = s.q;
        let h = 1e-5;
        let plus = hand.step(phi + h, &q).unwrap();
        let minus = hand.step(phi - h, &q).unwrap();
        for u in 0..4 {
            let dq = (plus.q[u] - minus.q[u]) / (2.0 * h);
            let d2q = (plus.dq[u] - minus.dq[u]) / (2.0 * h);
            assert!((dq - s.dq[u]).abs() <= 1e-6 * s.dq[u].abs().max(1.0), "dq[{u}] at {phi}: {dq} vs {}", s.dq[u]);
            assert!(
                (d2q - s.d2q[u]).abs() <= 1e-6 * s.d2q[u].abs().max(1.0),
                "d2q[{u}] at {phi}: {d2q} vs {}",
                s.d2q[u]
            );
        }
    }
}

/// The hand-written closed forms of the four-bar and of the gear-lever rocker (the references
/// of their timings) against kinloop over a turn, and their analogs against central differences
/// of their own positions (step 1e-4: truncation ~1e-8, rounding ~1e-12 / 1e-8 for `q''`).
#[test]
fn hand_closed_forms_match_kinloop_and_their_own_differences() {
    let four_bar = FOUR_BAR;
    let four_hand = FourBarClosed::of(&four_bar);
    let g = four_bar.solve(0.0).unwrap().q.into();
    for policy in WarmStart::ALL {
        let c = check_sweep(&Kinloop::<_, 2>::new(four_bar), &four_hand, STEPS, policy, g).unwrap();
        assert!(c.max_dev.iter().zip(EXACT).all(|(d, t)| *d <= t), "four-bar ({policy:?}): {c:?}");
    }
    let gear = gear_lever();
    let gear_hand = GearLeverClosed::of(&gear);
    let g = gear.solve(0.0).unwrap().q.into();
    for policy in WarmStart::ALL {
        let c = check_sweep(&Kinloop::<_, 2>::new(gear), &gear_hand, STEPS, policy, g).unwrap();
        assert!(c.max_dev.iter().zip(EXACT).all(|(d, t)| *d <= t), "gear lever ({policy:?}): {c:?}");
    }
    differences_agree(&four_hand);
    differences_agree(&gear_hand);
}

fn differences_agree<S: Stepper<2>>(s: &S) {
    let h = 1e-4;
    for k in 0..72 {
        let phi = k as f64 * std::f64::consts::TAU / 72.0 + 0.01;
        let (at, plus, minus) =
            (s.step(phi, &[0.0; 2]).unwrap(), s.step(phi + h, &[0.0; 2]).unwrap(), s.step(phi - h, &[0.0; 2]).unwrap());
        for u in 0..2 {
            let dq = (plus.q[u] - minus.q[u]) / (2.0 * h);
            let d2q = (plus.q[u] - 2.0 * at.q[u] + minus.q[u]) / (h * h);
            assert!((dq - at.dq[u]).abs() <= 1e-6 * at.dq[u].abs().max(1.0), "dq[{u}] at {phi}: {dq} vs {}", at.dq[u]);
            assert!(
                (d2q - at.d2q[u]).abs() <= 1e-5 * at.d2q[u].abs().max(1.0),
                "d2q[{u}] at {phi}: {d2q} vs {}",
                at.d2q[u]
            );
        }
    }
}
