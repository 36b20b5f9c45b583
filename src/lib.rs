//! # kinloop
//!
//! Kinematic analysis of planar mechanisms declared as **closed vector loops** (the method of
//! closed vector contours): each independent loop of the kinematic chain is one vector equation,
//! projected on X and Y. The [`mechanism!`] macro turns such a declaration, at compile time,
//! into straight-line numeric code for positions, velocity analogs `dq/dphi`, acceleration
//! analogs `d2q/dphi2`, true velocities and accelerations, and any named output (centres of
//! mass, coupler points). Every derivative comes from automatic differentiation of the declared
//! equations performed by the macro; nobody derives a derivative by hand.
//!
//! ```
//! kinloop::mechanism! {
//!     /// Offset slider-crank: crank `r` at the origin, rod `l`, slider on the line y = e.
//!     pub struct SliderCrank {
//!         params r = 1.0, l = 3.0, e = 0.2;
//!         input phi;
//!         unknowns psi = 0, x = r + l;
//!         loop oabo: r @ phi == (x, e) + l @ psi;
//!         point mid = r @ phi + 0.5 * l @ psi;
//!     }
//! }
//!
//! let m = SliderCrank::default();
//! let s = m.solve(0.3)?;                       // positions, analogs, outputs
//! assert!((s.q.x - (0.3f64.cos() - 3.0 * s.q.psi.cos())).abs() < 1e-12);
//! let v = s.motion(10.0, 0.0)?;                // crank at 10 rad/s: true motion
//! assert!((v.qdot.x - 10.0 * s.dq.x).abs() < 1e-12);
//! # Ok::<(), kinloop::Error>(())
//! ```
//!
//! ## The declaration language
//!
//! ```text
//! /// doc comment                            (kept on the generated struct)
//! #[kinloop(dense)]                          optional: solve all unknowns as one block
//! pub struct Name {
//!     params a, b = 2.5, c;                  design parameters (f64 fields; optional defaults)
//!     input phi;                             generalized coordinate(s): `inputs th1, th2;`
//!     unknowns q1 = 0.3, s = a + b;          unknowns, with initial guesses (default 0)
//!     let v = a @ phi + (0, c);              named intermediate (scalar or vector)
//!     loop name: vector == vector;           a closed contour: two scalar equations
//!     eq name: scalar == scalar;             one scalar equation
//!     point p = vector;                      named output point (x, y) and its analogs
//!     output w = scalar;                     named scalar output and its analogs
//! }
//! ```
//!
//! * `length @ angle` is a polar vector (`(length cos angle, length sin angle)`), `(x, y)` a
//!   Cartesian one; `+` and `-` chain vectors, a scalar scales a vector (`k * v`, `v / k`),
//!   `v.x` and `v.y` take components. `@` binds tighter than `+` and looser than `*`, so
//!   `a + 2 * r @ phi` is `a + ((2 r) @ phi)`, and an angle that is a sum needs parentheses:
//!   `r @ (phi + gamma)`.
//! * Scalars: numbers, `+ - * /`, unary `-`, powers `x ^ 2` (an integer exponent becomes
//!   `powi`), `pi`, and the functions `sin cos tan asin acos atan atan2(y, x) sqrt exp ln abs
//!   pow(x, y) hypot(a, b)`; for vectors `norm(v) dot(a, b) cross(a, b) angle(v) rot(v, theta)`.
//! * A loop's right side may be `0` (the zero vector): `loop c: a + b - c == 0;`.
//! * Time can be the input: `input t; let s1 = v1 * t;` (the analogs are then time derivatives).
//! * Several inputs make a multi-degree-of-freedom mechanism; the analogs are partial
//!   derivatives (`state.dq.phi2.th1` is `d phi2 / d th1`, `state.d2q.phi2.th1.th2` the mixed
//!   second derivative).
//! * The initial guesses choose the assembly mode (branch); pass another guess at run time to
//!   pick another branch, or warm-start each solve from the previous position along a sweep.
//!
//! Mistakes are compile errors at the exact place, with what to write instead: unknown names
//! (with a suggestion), vector/scalar mix-ups, unsupported functions, and structural problems
//! (equation and unknown counts with the resulting mobility, over- and under-determined parts).
//!
//! ## What is generated
//!
//! For `pub struct Name { ... }`:
//!
//! * `Name`: the parameters as public `f64` fields (and `Default` when every parameter has a
//!   default value);
//! * `NameInputs<T>`, `NameUnknowns<T>`, `NameOutputs<T>`: named fields (points are
//!   [`Vec2`]), convertible from and to arrays (and nalgebra vectors for the unknowns);
//! * `NameState`: positions `q`, velocity analogs `dq`, acceleration analogs `d2q`, outputs
//!   `out`, `dout`, `d2out`, the solver [`SolveReport`] and the blocks' [`Health`];
//!   `state.motion(omega, eps)` gives true velocities and accelerations (`NameMotion`);
//! * methods on `Name`: `solve`, `kinematics(input, guess)`, `position(input, guess)`,
//!   `kinematics_at(input, q)`, `outputs`, `residual`, `guess`, `check`, their `_with`
//!   variants taking a [`NewtonConfig`], and the constants `PARAMS`, `INPUTS`, `UNKNOWNS`,
//!   `EQUATIONS`, `OUTPUTS`, `BLOCKS` (the block-triangular decomposition);
//! * an implementation of [`Mechanism`] for generic code.
//!
//! The equations are ordered into blocks (maximum matching and Tarjan's strongly connected
//! components, i.e. the block-lower-triangular form): each block is solved by its own small
//! Newton with a fixed-size Jacobian, blocks whose unknowns appear linearly (slider coordinates)
//! by one linear solve. Velocity analogs solve `J q' = -df/dphi` and acceleration analogs
//! `J q'' = -D2f[(q', 1), (q', 1)]` with one factorisation per block shared by both.
//!
//! ## Errors
//!
//! Bad input never panics and never yields a silent NaN: see [`Error`] (non-finite parameters or
//! inputs, no convergence, a mechanism that cannot be assembled, a singular position, an
//! expression outside its domain), each carrying the mechanism, the input values and the block.
//!
//! ```
//! kinloop::mechanism! {
//!     pub struct FourBar {
//!         params a, b, c, d;
//!         input phi;
//!         unknowns beta = 0.5, gamma = 1.5;
//!         loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
//!     }
//! }
//! // Links too short to close the loop:
//! let m = FourBar { a: 1.0, b: 1.0, c: 1.0, d: 5.0 };
//! let err = m.solve(0.0).unwrap_err();
//! assert!(matches!(err, kinloop::Error::NoAssembly { .. }), "{err}");
//! let bad = FourBar { a: f64::NAN, ..m };
//! assert!(matches!(bad.solve(0.0), Err(kinloop::Error::NonFinite { .. })));
//! ```
extern crate self as kinloop;

pub use kinloop_macros::mechanism;
pub use kinloop_runtime::*;

#[doc(hidden)]
pub mod __private {
    pub use kinloop_runtime::*;
}
