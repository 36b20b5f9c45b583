//! Machine dynamics from the kinematic state: the exact reduced moment of inertia and its
//! slope (the mass matrix and velocity-product terms for several inputs), generalised forces by
//! virtual power, inverse dynamics over a cycle (driving torque, shaking force and moment and
//! their harmonics), flywheel sizing, and forward simulation.
//!
//! A [`MassModel`] lists rigid bodies (mass, centre of mass as two coordinates read from the
//! state (output columns, unknowns or constants), moment of inertia about it, the angle it rotates with), loads (forces at points and
//! torques on angles, constant or laws of the state), and gravity. Everything is computed from
//! the velocity and acceleration analogs kinloop already generates: see [`eval`] for the
//! formulas.
//!
//! The formulas are written once over any kinematic state ([`AnalogState`]: a compiled
//! mechanism's [`Kin`](crate::Kin) or a run-time model's [`KinBuf`](crate::dims::KinBuf)), so a
//! mechanism read at run time has the same dynamics: [`MassModelBuf`] holds its bodies and
//! gravity with the sizes it learns when read (its loads' values computed by the model and
//! given to each evaluation), and [`Cycle::over_turn`] sweeps a turn of any
//! [`Kernel`](crate::Kernel)'s input and evaluates each state as the sweep makes it: the inverse
//! cycle [`InverseCycle::run`] computes, keeping no state ([`turn_states`] keeps them). The forward simulation is written once too
//! ([`simulate_of()`], over any [`Kernel`](crate::Kernel), its step written in place):
//! [`Simulation::run`] is it over a compiled mechanism. [`simulate_steps_of()`] and
//! [`Simulation::run_steps`] hand each accepted step (its [`DenseStep`]) to the caller as it is
//! made and keep nothing: the recorded [`Trajectory`] is one consumer of them.
//!
//! ```
//! use kinloop_runtime::dynamics::{Body, Coord, MassModel, Rotation};
//! use kinloop_runtime::{Health, Kin, SolveReport, NewtonStop};
//!
//! // A crank of radius 0.1 turning with input 0, its centre of mass at the crank pin, in a
//! // hand-made state (the columns of a point `p = r @ phi` at phi = 0).
//! let r = 0.1;
//! let k: Kin<0, 1, 2> = Kin {
//!     x: [0.0], q: [], dq: [], d2q: [],
//!     out: [r, 0.0], dout: [[0.0], [r]], d2out: [[[-r]], [[0.0]]],
//!     report: SolveReport { iterations: 0, evaluations: 0, residual: 0.0, termination: NewtonStop::Direct },
//!     health: Health::default(),
//! };
//! let model = MassModel::new()
//!     .with_body(Body { name: "crank".into(), mass: 2.0, com: [Coord::Output(0), Coord::Output(1)], inertia: 0.01, rotation: Rotation::Input(0) })?
//!     .with_gravity([0.0, -9.81])?;
//! let d = model.dynamics(&k, &[10.0])?;
//! // J = m r^2 + J_S, constant: J' = 0; gravity pulls the horizontal crank down: Q = -m g r.
//! assert!((d.reduced_inertia() - (2.0 * r * r + 0.01)).abs() < 1e-15);
//! assert!(d.reduced_inertia_slope().abs() < 1e-15);
//! assert!((d.forces[0] + 2.0 * 9.81 * r).abs() < 1e-14);
//! // Bad input is a typed error.
//! let bad = MassModel::<0, 1, 2>::new().with_body(Body { name: "crank".into(), mass: -1.0, com: [Coord::Output(0), Coord::Fixed(0.0)], inertia: 0.0, rotation: Rotation::None });
//! assert!(matches!(bad, Err(kinloop_runtime::dynamics::DynamicsError::BadMass { .. })));
//! # Ok::<(), kinloop_runtime::dynamics::DynamicsError>(())
//! ```

pub mod cycle;
pub mod error;
pub mod eval;
pub mod model;
pub mod ode;
pub mod simulate;
pub mod simulate_of;
pub mod sized;
pub mod state;
mod terms;

#[cfg(test)]
mod robust_tests;

pub use cycle::{Cycle, CyclePoint, Flywheel, InverseCycle, MIN_DELTA, SpeedLaw, each_turn_state, turn_states};
pub use error::DynamicsError;
pub use eval::{Dynamics, Shaking};
pub use model::{Body, Coord, ForceLaw, Load, MassModel, Point, Rotation, TorqueLaw};
pub use ode::{DenseStep, MIN_RTOL, OdeConfig, dopri5};
pub use simulate::Simulation;
// The recorded runs' storage, shared with the run-time models' `run` (kinloop-model): no API
// of its own, since `run` records every step and `run_steps` keeps none.
#[doc(hidden)]
pub use simulate_of::Recording;
pub use simulate_of::{RunConfig, Trajectory, simulate_of, simulate_steps_of};
pub use sized::{Applied, DynamicsBuf, MassModelBuf};
pub use state::AnalogState;
