//! A step whose checks are deferred to the kernel's end answers exactly what the checked kernel
//! answers: the same state, bit for bit, or the same error (block, input, guess and all). The
//! step kernel of a small mechanism tests nothing on the way and one condition at its end; the
//! checked kernel (`Mechanism::kinematics_step_checked`) tests every root, guess, angle and
//! pivot where it arises. Compared here over inputs and guesses that reach every failure: links
//! that cannot reach, a pin over its pivot, change points, non-finite inputs and guesses, angles
//! too many turns out (under the default configuration and that of the smallest residual
//! tolerance), guesses around the entry test's bound (the configured one less a margin) and
//! angles around the configured one, a Newton block fed by a closed form that failed, and parameters non-finite,
//! zero, negative, huge or tiny. (The deferred kernel's end sums only the values whose
//! finiteness the others' does not imply: a value left out that the sum missed would show as a
//! state where the checked kernel finds an error.)

use kinloop::__gen::{ByValue, Libm};
use kinloop::{Mechanism, NewtonConfig, Sensitivities};
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::{ClassFourCore, FiveBar, FourBar, RhombicDrive, SliderCrank};
use std::f64::consts::TAU;

kinloop::mechanism! {
    /// A four-bar's dyad (closed form) feeding a block no closed form matches (Newton): the
    /// angle `psi` of a link whose direction is `psi + sin(psi) / 10`, and a slider `s`.
    pub struct DyadThenNewton {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2, e = 2.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, psi = 0.3, s = 5.0;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop ext: (d, 0) + c @ gamma + e @ (psi + 0.1 * sin(psi)) == (s, 1.0);
    }
}

/// What the two kernels answered, and of which kinds.
#[derive(Default, Debug)]
struct Tally {
    states: usize,
    errors: Vec<String>,
}

/// Both kernels at `(x, guess)`: the same `Debug` text (shortest round-trip floats, so the
/// same bits; errors with every field).
fn agree<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    x: [f64; NI],
    guess: [f64; N],
    tally: &mut Tally,
) {
    // The default configuration (the entry test's bound 4.5e6 rad) and, for guesses between
    // 16,000 rad, the bound of the smallest residual tolerance, and the default bound, that
    // configuration too (the guesses beyond both, or NaN, take the same path under both).
    let configs = [NewtonConfig::default(), NewtonConfig::default().with_residual_tol(16.0 * f64::EPSILON)];
    let far = guess.iter().any(|g| g.abs() > 1e4 && g.abs() < 1e6);
    for cfg in &configs[..if far { 2 } else { 1 }] {
        let deferred = m.kinematics_step_sink::<_, _, false>(&x, &guess, cfg, &mut Libm, ByValue);
        let checked = m.kinematics_step_checked(&x, &guess, cfg, &mut Libm, ByValue);
        let (d, c) = (format!("{deferred:?}"), format!("{checked:?}"));
        assert_eq!(d, c, "{} at {x:?} from {guess:?}", M::NAME);
        match deferred {
            Ok(_) => tally.states += 1,
            Err(e) => tally.errors.push(format!("{e:?}").split([' ', '{', '(']).next().unwrap_or("").to_owned()),
        }
    }
}

/// Inputs over two turns, with the non-finite ones.
fn inputs() -> Vec<f64> {
    let mut x: Vec<f64> = (0..=96).map(|k| -TAU + TAU * k as f64 / 48.0).collect();
    x.extend([f64::NAN, f64::INFINITY, -f64::INFINITY, 1e5]);
    x
}

/// From `base`: itself; moved by whole turns (the configured bound is 4.5e6 rad by default,
/// the entry test's 8 less, and 16,000 at the smallest residual tolerance: 1e5 passes both
/// tests under the default and neither under the smallest; 4,503,584 puts the guesses' sum
/// around the default entry bound, the angles around the configured one; 1e7 passes neither);
/// each entry NaN in turn; and moved by up to 3 in each entry (the other assembly mode, often).
fn guesses<const N: usize>(base: [f64; N], k: usize) -> Vec<[f64; N]> {
    let mut out =
        vec![base, base.map(|g| g + 15_915.0 * TAU), base.map(|g| g + 716_770.0 * TAU), base.map(|g| g + 1e7)];
    for i in 0..N {
        let mut g = base;
        g[i] = f64::NAN;
        out.push(g);
    }
    let mut g = base;
    for (i, v) in g.iter_mut().enumerate() {
        *v += 3.0 * (((k * 7 + i * 3) % 11) as f64 / 5.0 - 1.0);
    }
    out.push(g);
    out
}

/// Every input against every guess of the mechanism's own guess there.
fn sweep_all<M: Mechanism<N, 1, NO>, const N: usize, const NO: usize>(m: &M) -> Tally {
    let mut tally = Tally::default();
    for (k, x) in inputs().into_iter().enumerate() {
        for g in guesses(m.guess_flat(&[x]), k) {
            agree(m, [x], g, &mut tally);
        }
    }
    tally
}

impl Tally {
    fn add(&mut self, other: Tally) {
        self.states += other.states;
        self.errors.extend(other.errors);
    }

    /// The comparisons met states, and errors of every kind in `kinds`.
    fn met(&self, kinds: &[&str]) {
        let mut seen: Vec<&str> = self.errors.iter().map(String::as_str).collect();
        seen.sort_unstable();
        seen.dedup();
        println!("{} states; errors: {seen:?}", self.states);
        for k in kinds {
            assert!(seen.contains(k), "no {k} among {seen:?}");
        }
        assert!(self.states > 100, "{} states", self.states);
    }
}

#[test]
fn four_bars_with_gaps_and_change_points() {
    // Crank-rocker; non-Grashof (gaps in the crank's turn); a parallelogram (change points,
    // where the Jacobian is singular).
    let mut tally = Tally::default();
    for m in [
        FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 },
        FourBar { a: 2.0, b: 1.5, c: 2.0, d: 3.0 },
        FourBar { a: 1.0, b: 2.0, c: 1.0, d: 2.0 },
    ] {
        tally.add(sweep_all(&m));
    }
    tally.met(&["NoAssembly", "NonFinite", "Singular", "TooManyTurns"]);
}

#[test]
fn slider_cranks_and_the_rhombic_drive() {
    // A rod shorter than crank plus offset cannot follow the whole turn.
    let mut tally = Tally::default();
    for m in [SliderCrank { r: 1.0, l: 3.0, e: 0.5 }, SliderCrank { r: 1.0, l: 1.2, e: 0.5 }] {
        tally.add(sweep_all(&m));
    }
    tally.met(&["NoAssembly", "NonFinite", "TooManyTurns"]);
    let mut tally = sweep_all(&RhombicDrive::default());
    tally.add(sweep_all(&RhombicDrive { l_p: 1.2, l_b: 1.1, ..RhombicDrive::default() }));
    tally.met(&["NoAssembly", "NonFinite", "TooManyTurns"]);
}

#[test]
fn a_pin_over_its_pivot() {
    // Equal arms: the pin passes through the rocker's pivot at alpha = pi/3, where the polar
    // length is zero and its angle undetermined.
    let m = GearLever { l_c: 1.3, l_p: 1.3, u: 3.0 };
    let mut tally = sweep_all(&m);
    for x in [TAU / 6.0, TAU / 6.0 + 1e-9, -TAU / 3.0 * 2.5] {
        for g in guesses(m.guess_flat(&[x]), 1) {
            agree(&m, [x], g, &mut tally);
        }
    }
    tally.add(sweep_all(&GearLever::default()));
    tally.met(&["NonFinite", "Singular", "TooManyTurns"]);
}

#[test]
fn two_inputs() {
    let m = FiveBar::default();
    let mut tally = Tally::default();
    for (k, x) in inputs().into_iter().enumerate() {
        let x = [x, 0.7 * x + 1.0];
        for g in guesses(m.guess_flat(&x), k) {
            agree(&m, x, g, &mut tally);
        }
    }
    tally.met(&["NonFinite", "TooManyTurns"]);
}

#[test]
fn newton_blocks_alone_and_after_a_failed_closed_form() {
    // A Newton block that fails returns the checked kernel's answer: here the closed form's
    // error before it, whose NaN reached the Newton block unchecked.
    let mut tally = sweep_all(&ClassFourCore::default());
    tally.add(sweep_all(&DyadThenNewton { a: 2.0, b: 1.5, c: 2.0, d: 3.0, e: 2.0 }));
    tally.add(sweep_all(&DyadThenNewton::default()));
    tally.met(&["NoAssembly", "NoConvergence", "NonFinite", "TooManyTurns"]);
}

/// Every parameter in turn NaN, infinite, zero, negative, huge (its square overflows) or tiny
/// (its square underflows).
#[test]
fn extreme_parameters() {
    const VALUES: [f64; 7] = [f64::NAN, f64::INFINITY, -f64::INFINITY, 0.0, -1.0, 1e300, 1e-300];
    let mut tally = Tally::default();
    for v in VALUES {
        for k in 0..4 {
            let mut p = [1.0, 3.0, 2.5, 3.2];
            p[k] = v;
            tally.add(sweep_all(&FourBar { a: p[0], b: p[1], c: p[2], d: p[3] }));
        }
        for k in 0..3 {
            let mut p = [1.0, 3.0, 0.5];
            p[k] = v;
            tally.add(sweep_all(&SliderCrank { r: p[0], l: p[1], e: p[2] }));
            let mut p = [2.0, 1.3, 3.0];
            p[k] = v;
            tally.add(sweep_all(&GearLever { l_c: p[0], l_p: p[1], u: p[2] }));
        }
        let rhombic = RhombicDrive::default();
        for k in 0..rhombic.params_flat().len() {
            let mut p = rhombic.params_flat();
            p[k] = v;
            tally.add(sweep_all(&rhombic.with_params_flat(p)));
        }
    }
    tally.met(&["NoAssembly", "NonFinite", "Singular"]);
}
