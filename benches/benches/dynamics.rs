//! One dynamics evaluation (reduced inertia `J`, `dJ/dphi` and the generalised force of a
//! state-dependent gas force and gravity) against the kinematic step it needs, on the rhombic
//! drive with the centres of mass of its crank and rods, five bodies in all. Each variant steps
//! to the next of 1,000,000 equally spaced crank angles per turn, warm-started from the previous
//! step:
//!
//! * `kinematics`: positions, velocity and acceleration analogs, outputs (`kinematics_flat`);
//! * `kinematics_dynamics`: the same plus the dynamics evaluation;
//! * `dynamics`: the dynamics evaluation alone, on states solved beforehand (one turn at 3,600
//!   angles, cycled).
//!
//! `cargo bench -p kinloop-bench --bench dynamics`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use kinloop::dynamics::{Body, Coord, MassModel, Rotation};
use kinloop::{Kin, Mechanism, NewtonConfig};
use kinloop_fixtures::RhombicDrive as RhombicDrivePaper;

const STEPS: usize = 1_000_000;

fn model() -> MassModel<4, 1, 7> {
    let out = |c: usize| [Coord::Output(2 * c), Coord::Output(2 * c + 1)];
    let bodies = [
        Body { name: "crank".into(), mass: 2.0, com: out(0), inertia: 0.05, rotation: Rotation::Input(0) },
        Body { name: "working rod".into(), mass: 0.8, com: out(1), inertia: 0.6, rotation: Rotation::Unknown(0) },
        Body { name: "displacer rod".into(), mass: 0.9, com: out(2), inertia: 0.9, rotation: Rotation::Unknown(1) },
        Body {
            name: "piston".into(),
            mass: 1.5,
            com: [Coord::Unknown(2), Coord::Fixed(0.0)],
            inertia: 0.0,
            rotation: Rotation::None,
        },
        Body {
            name: "displacer".into(),
            mass: 1.1,
            com: [Coord::Unknown(3), Coord::Fixed(0.9)],
            inertia: 0.0,
            rotation: Rotation::None,
        },
    ];
    let mut m = MassModel::new().with_gravity([0.0, -9.81]).unwrap();
    for b in bodies {
        m = m.with_body(b).unwrap();
    }
    m.with_force("gas", [Coord::Unknown(2), Coord::Fixed(0.0)], |k: &Kin<4, 1, 7>, _: &[f64; 1]| {
        [-20.0 / (k.q[2] + 4.6).powi(2), 0.0]
    })
    .unwrap()
}

fn bench(c: &mut Criterion) {
    let drive = RhombicDrivePaper::default();
    let model = model();
    let cfg = NewtonConfig::default();
    let mut g = c.benchmark_group("dynamics");
    g.measurement_time(Duration::from_secs(5));
    g.bench_function("kinematics", |b| {
        b.iter_custom(|iters| {
            steps(&drive, &cfg, iters, |k| {
                black_box(k);
            })
        })
    });
    g.bench_function("kinematics_dynamics", |b| {
        b.iter_custom(|iters| {
            steps(&drive, &cfg, iters, |k| {
                black_box(model.dynamics(k, &[1.0]).unwrap());
            })
        })
    });
    let mut q = drive.guess_flat(&[0.0]);
    let states: Vec<Kin<4, 1, 7>> = (0..3600)
        .map(|j| {
            let k = drive.kinematics_flat(&[j as f64 * std::f64::consts::TAU / 3600.0], &q, &cfg).unwrap();
            q = k.q;
            k
        })
        .collect();
    let mut j = 0usize;
    g.bench_function("dynamics", |b| {
        b.iter(|| {
            j = (j + 1) % states.len();
            black_box(model.dynamics(black_box(&states[j]), &[1.0]).unwrap());
        })
    });
    g.finish();
}

/// `iters` kinematic steps along turns of [`STEPS`] angles, each warm-started from the previous
/// one and handed to `then`, and the time they took. Out of line with the mechanism borrowed
/// shared, as the lean harness's loops (`benches/benches/step.rs`, `lean_loop`): the sines and
/// cosines of the drive's parameter angles (`gamma`, `psi_s1`) are computed once, where a loop
/// in criterion's `iter` closure computes them at every step.
#[inline(never)]
fn steps(drive: &RhombicDrivePaper, cfg: &NewtonConfig, iters: u64, then: impl Fn(&Kin<4, 1, 7>)) -> Duration {
    let dphi = std::f64::consts::TAU / STEPS as f64;
    let mut q = drive.guess_flat(&[0.0]);
    let start = Instant::now();
    for n in 0..iters as usize {
        let k = drive.kinematics_flat(&[(n % STEPS) as f64 * dphi], &q, cfg).unwrap();
        q = k.q;
        then(&k);
    }
    start.elapsed()
}

criterion_group!(benches, bench);
criterion_main!(benches);
