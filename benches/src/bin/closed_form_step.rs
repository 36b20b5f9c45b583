//! Steps of the rhombic drive for instruction counts under callgrind: `closed_form_step VARIANT
//! STEPS` runs `STEPS` steps of one turn of 720 (0.5 degree) with one of
//! * `hand`: the paper's closed form written by hand;
//! * `point`: kinloop's `kinematics_flat` from the previous position (closed-form blocks);
//! * `newton`: the same with `#[kinloop(newton)]`;
//! * `sweep`: kinloop's own `Sweep`; `newton-sweep`: the same with `#[kinloop(newton)]`.
//!
//! Instructions per step = difference of the totals of two runs with different `STEPS`, divided
//! by the difference of the steps (the setup cancels).

use std::hint::black_box;

use kinloop_bench::decls::RhombicDrive;
use kinloop_bench::kinloop_variants::{Kinloop, KinloopSweep};
use kinloop_bench::rhombic::{ClosedForm, PARAMS, initial_guess};
use kinloop_bench::sweep::{Stepper, Sweep, WarmStart};

kinloop::mechanism! {
    /// The rhombic drive of the benchmarks, solved by Newton in every block.
    #[kinloop(newton)]
    pub struct RhombicNewton {
        params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, de = 0.9, gamma = 0.7;
        input phi1;
        unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
    }
}

const TURN: usize = 720;

fn steps_of<S: Stepper<4>>(s: &S, steps: usize) -> f64 {
    let mut sweep = Sweep::start(s, TURN, WarmStart::Previous, initial_guess(&PARAMS)).expect("start");
    let mut acc = 0.0;
    for _ in 0..steps {
        acc += black_box(sweep.advance(s).expect("step")).q[0];
    }
    acc
}

fn sweep_of<M: kinloop::Mechanism<4, 1, 0>>(m: &M, steps: usize) -> f64 {
    let mut s = KinloopSweep::start(m, TURN, initial_guess(&PARAMS)).expect("start");
    let mut acc = 0.0;
    for _ in 0..steps {
        acc += black_box(s.advance().expect("step")).q[0];
    }
    acc
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let variant = args.get(1).map_or("point", String::as_str);
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(10_000);
    let m = PARAMS.kinloop();
    let acc = match variant {
        "hand" => steps_of(&ClosedForm::new(&PARAMS), steps),
        "point" => steps_of(&Kinloop::<RhombicDrive, 0>::new(m), steps),
        "newton" => steps_of(&Kinloop::<RhombicNewton, 0>::new(RhombicNewton::default()), steps),
        "sweep" => sweep_of(&m, steps),
        "newton-sweep" => sweep_of(&RhombicNewton::default(), steps),
        other => panic!("unknown variant {other}: hand, point, newton or sweep"),
    };
    println!("{variant}: {steps} steps, checksum {acc}");
}
