//! Shared by every test binary: plain numerics for the independent checks (closed forms solved
//! without kinloop), the reference constructions several tests need, named tolerances
//! ([`tol`]), `assert_close!`, and the Newton configurations references are solved with.

use kinloop::{Mechanism, NewtonConfig};
use kinloop_fixtures::FiveBar;
use std::f64::consts::{PI, TAU};

pub mod doc_snippets;
pub mod tol;

/// A property test's configuration: `cases` cases from the fixed `seed`, the same on every run
/// (as CI runs them), no failure files; unless the environment asks for a stress run by hand:
/// `STRESS_SEED` another seed, `STRESS_MULT` that many times the cases, e.g.
/// `STRESS_SEED=107 STRESS_MULT=25 cargo test --release --test sweeps sweep_any_step` (a case
/// one finds belongs in the test as a fixed case).
pub fn fixed_seed(seed: u64, cases: u32) -> proptest::test_runner::Config {
    let env = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<u64>().ok());
    let mult = env("STRESS_MULT").map_or(1, |m| u32::try_from(m).unwrap_or(u32::MAX).max(1));
    proptest::test_runner::Config {
        cases: cases.saturating_mul(mult),
        failure_persistence: None,
        rng_seed: proptest::test_runner::RngSeed::Fixed(env("STRESS_SEED").unwrap_or(seed)),
        ..proptest::test_runner::Config::default()
    }
}

/// Declares a mechanism twice from one body: as `$name` (closed forms where recognised) and as
/// `$newton` with `#[kinloop(newton)]`, so that the two cannot drift apart.
macro_rules! with_newton_twin {
    ($(#[doc = $doc:literal])* pub struct $name:ident, $newton:ident { $($body:tt)* }) => {
        kinloop::mechanism! {
            $(#[doc = $doc])*
            pub struct $name { $($body)* }
        }
        kinloop::mechanism! {
            $(#[doc = $doc])*
            #[kinloop(newton)]
            pub struct $newton { $($body)* }
        }
    };
}

/// Asserts that `actual` is within a tolerance of `expected`, and on failure prints both, their
/// difference, the tolerance and a label (by default the expression of `actual`; a format
/// string and its arguments otherwise).
///
/// * `assert_close!(actual, expected, tol)`: `|actual - expected| < tol`, absolute;
/// * `assert_close!(actual, expected, <= tol)`: `|actual - expected| <= tol`, absolute, for a
///   bound that may be met exactly;
/// * `assert_close!(actual, expected, rel = tol)`: [`close`]`(actual, expected, tol)`, i.e.
///   `|actual - expected| <= tol * max(1, |expected|)`, relative and absolute near zero.
///
/// A NaN on either side fails both forms.
macro_rules! assert_close {
    ($actual:expr, $expected:expr, rel = $tol:expr $(,)?) => {
        assert_close!($actual, $expected, rel = $tol, "{}", stringify!($actual))
    };
    ($actual:expr, $expected:expr, rel = $tol:expr, $($label:tt)+) => {{
        let (actual, expected, tol): (f64, f64, f64) = ($actual, $expected, $tol);
        assert!(
            $crate::support::close(actual, expected, tol),
            "{}: expected {expected:e}, actual {actual:e}, difference {:e}, tolerance {tol:e} relative ({:e} absolute)",
            format_args!($($label)+),
            (actual - expected).abs(),
            tol * expected.abs().max(1.0),
        );
    }};
    ($actual:expr, $expected:expr, <= $tol:expr $(,)?) => {
        assert_close!($actual, $expected, <= $tol, "{}", stringify!($actual))
    };
    ($actual:expr, $expected:expr, <= $tol:expr, $($label:tt)+) => {{
        let (actual, expected, tol): (f64, f64, f64) = ($actual, $expected, $tol);
        assert!(
            (actual - expected).abs() <= tol,
            "{}: expected {expected:e}, actual {actual:e}, difference {:e}, tolerance {tol:e} (inclusive)",
            format_args!($($label)+),
            (actual - expected).abs(),
        );
    }};
    ($actual:expr, $expected:expr, $tol:expr $(,)?) => {
        assert_close!($actual, $expected, $tol, "{}", stringify!($actual))
    };
    ($actual:expr, $expected:expr, $tol:expr, $($label:tt)+) => {{
        let (actual, expected, tol): (f64, f64, f64) = ($actual, $expected, $tol);
        assert!(
            (actual - expected).abs() < tol,
            "{}: expected {expected:e}, actual {actual:e}, difference {:e}, tolerance {tol:e}",
            format_args!($($label)+),
            (actual - expected).abs(),
        );
    }};
}

/// Random numbers from a fixed seed (xorshift): the same cases at every run, with no
/// dependency. `unit` is uniform in `[0, 1)`.
pub struct Xorshift(pub u64);

impl Xorshift {
    /// The next number, uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A root of `f` in `[lo, hi]` by bisection; `f` must change sign there.
pub fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    let flo = f(lo);
    assert!(flo * f(hi) < 0.0, "no sign change on [{lo}, {hi}]");
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if (f(mid) < 0.0) == (flo < 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Where `f` is largest on `[0, span)`: the best of `n` equally spaced samples, refined by golden
/// sections within one spacing on either side.
pub fn argmax(f: impl Fn(f64) -> f64, span: f64, n: usize) -> f64 {
    let best = (0..n).map(|i| span * i as f64 / n as f64).max_by(|a, b| f(*a).total_cmp(&f(*b))).unwrap();
    let h = span / n as f64;
    let (mut lo, mut hi) = (best - h, best + h);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let (c, d) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if f(c) > f(d) {
            hi = d;
        } else {
            lo = c;
        }
    }
    0.5 * (lo + hi)
}

/// Where `f` is stationary in `[lo, hi]`: a root of its Richardson-extrapolated central
/// difference (step 1e-3, truncation ~1e-15 |f^(5)|, rounding ~1e-13 |f|) by bisection; the
/// derivative must change sign there. Located to ~1e-13 / |f''|.
pub fn stationary(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    bisect(|x| richardson_first(&f, x, 1e-3), lo, hi)
}

/// `|a - b| <= rel * max(1, |b|)`: relative tolerance, absolute near zero.
pub fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1.0)
}

/// An angle wrapped into `[-pi, pi)`.
pub fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(TAU) - PI
}

/// The distance of two angles modulo whole turns, in `[0, pi]`.
pub fn angle_apart(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d)
}

/// Central differences with one Richardson step (h and h/2): (first, second) derivative with
/// truncation error O(h^4) (~h^4/480 |q^(5)| and less for the second); position errors e
/// contribute ~e/h and ~5e/h^2.
pub fn richardson(f: impl Fn(f64) -> f64, x: f64, h: f64) -> (f64, f64) {
    let d2 = |h: f64| (f(x + h) - 2.0 * f(x) + f(x - h)) / (h * h);
    (richardson_first(&f, x, h), (4.0 * d2(h / 2.0) - d2(h)) / 3.0)
}

/// The first derivative of `f` at `x` by central differences with one Richardson step (h and
/// h/2): truncation error ~h^4/480 |f^(5)|; errors e in the values contribute ~e/h.
pub fn richardson_first(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
    let d1 = |h: f64| (f(x + h) - f(x - h)) / (2.0 * h);
    (4.0 * d1(h / 2.0) - d1(h)) / 3.0
}

/// Every analog of `m` at the inputs `x` (solved from `q`) beside a reference of its own, as
/// `(what, analog, reference)`: the central difference with one Richardson step
/// ([`richardson_first`], steps `h` and `h / 2`) along input `i` of the positions and outputs
/// for their first analogs by `x_i`, and of the velocity analogs by `x_j` for their second
/// analogs by `x_i, x_j`, every ordered pair `(i, j)`, so each cross derivative is checked twice,
/// from both inputs' analogs. A second analog is the first derivative of a velocity analog (exact
/// at its position), so both references are good to [`tol::FD_FIRST`] relative: at `h = 1e-3`
/// truncation ~h^4/480 |f^(5)| ~ 2e-15 |f^(5)|, and positions converged to rounding
/// ([`newton_to_fine_step`], errors e ~ 1e-15) contribute ~e/h ~ 1e-12.
pub fn analogs_against_differences<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    x: [f64; NI],
    q: &[f64; N],
    h: f64,
) -> Vec<(String, f64, f64)>
where
    M: Mechanism<N, NI, NO>,
{
    let cfg = newton_to_fine_step();
    let at = |x: [f64; NI]| m.kinematics_flat(&x, q, &cfg).unwrap_or_else(|e| panic!("{} at {x:?}: {e}", M::NAME));
    let k = at(x);
    let mut checks = Vec::new();
    for i in 0..NI {
        let along = |t: f64| {
            let mut y = x;
            y[i] = t;
            at(y)
        };
        let by = |f: &dyn Fn(&kinloop::Kin<N, NI, NO>) -> f64| richardson_first(|t| f(&along(t)), x[i], h);
        let xi = M::INPUTS[i];
        for u in 0..N {
            let name = M::UNKNOWNS[u];
            checks.push((format!("d{name}/d{xi}"), k.dq[u][i], by(&|s| s.q[u])));
            for j in 0..NI {
                let what = format!("d2{name}/d{xi} d{}", M::INPUTS[j]);
                checks.push((what, k.d2q[u][i][j], by(&|s| s.dq[u][j])));
            }
        }
        for o in 0..NO {
            let name = M::OUTPUTS[o];
            checks.push((format!("d{name}/d{xi}"), k.dout[o][i], by(&|s| s.out[o])));
            for j in 0..NI {
                let what = format!("d2{name}/d{xi} d{}", M::INPUTS[j]);
                checks.push((what, k.d2out[o][i][j], by(&|s| s.dout[o][j])));
            }
        }
    }
    checks
}

/// C from the circles (B, rb) and (D, rd), on side `side` of B -> D (+1 left, -1 right).
pub fn circle_point(bx: f64, by: f64, rb: f64, dx: f64, dy: f64, rd: f64, side: f64) -> (f64, f64) {
    let (ux, uy) = (dx - bx, dy - by);
    let dist = ux.hypot(uy);
    let along = (rb * rb - rd * rd + dist * dist) / (2.0 * dist);
    let h = (rb * rb - along * along).max(0.0).sqrt();
    (bx + (along * ux - side * h * uy) / dist, by + (along * uy + side * h * ux) / dist)
}

/// Joint C of the four-bar O-B-C-D (crank `a` from O at `phi`, coupler `b`, rocker `c`, frame
/// `d` from O along x) from the circles (B, b) and (D, c), on side `side` of B -> D (+1 left,
/// -1 right); `None` where the circles do not meet.
pub fn four_bar_joint(a: f64, b: f64, c: f64, d: f64, phi: f64, side: f64) -> Option<(f64, f64)> {
    let (bx, by) = (a * phi.cos(), a * phi.sin());
    let dist = (d - bx).hypot(by);
    if dist > b + c || dist < (b - c).abs() {
        return None;
    }
    Some(circle_point(bx, by, b, d, 0.0, c, side))
}

/// The four-bar's coupler and rocker angles `[beta, gamma]` at crank angle `x` (as
/// [`four_bar_angles`]), each `[position, first, second]` by `x`, differentiated by hand from
/// `a e(x) + b e(beta) = d + c e(gamma)`: `beta' = a sin(gamma - x) / (b sin(beta - gamma))`,
/// `gamma' = a sin(beta - x) / (c sin(beta - gamma))`, and with
/// `R = a e(x) + b beta'^2 e(beta) - c gamma'^2 e(gamma)`,
/// `beta'' = -Re(R e(-gamma)) / (b sin(beta - gamma))`,
/// `gamma'' = Re(R e(-beta)) / (c sin(gamma - beta))`. `None` where it cannot be assembled.
pub fn four_bar_jets(a: f64, b: f64, c: f64, d: f64, x: f64, side: f64) -> Option<[[f64; 3]; 2]> {
    let [beta, gamma] = four_bar_angles(a, b, c, d, x, side)?;
    let s = (beta - gamma).sin();
    let beta1 = a * (gamma - x).sin() / (b * s);
    let gamma1 = a * (beta - x).sin() / (c * s);
    let along_gamma = a * (x - gamma).cos() + b * beta1 * beta1 * (beta - gamma).cos() - c * gamma1 * gamma1;
    let along_beta = a * (x - beta).cos() + b * beta1 * beta1 - c * gamma1 * gamma1 * (gamma - beta).cos();
    Some([[beta, beta1, -along_gamma / (b * s)], [gamma, gamma1, along_beta / (c * -s)]])
}

/// The four-bar's coupler and rocker angles (of B -> C and D -> C) at `phi`, from
/// [`four_bar_joint`]; `None` where it cannot be assembled.
pub fn four_bar_angles(a: f64, b: f64, c: f64, d: f64, phi: f64, side: f64) -> Option<[f64; 2]> {
    let (cx, cy) = four_bar_joint(a, b, c, d, phi, side)?;
    let (bx, by) = (a * phi.cos(), a * phi.sin());
    Some([(cy - by).atan2(cx - bx), cy.atan2(cx - d)])
}

/// The crank angle in `[0, pi]` where the four-bar's diagonal `|BD|` equals `r` (`b + c`: coupler
/// and rocker stretched, `|b - c|`: folded), by the law of cosines; NaN where it never does.
pub fn four_bar_limit(a: f64, d: f64, r: f64) -> f64 {
    ((a * a + d * d - r * r) / (2.0 * a * d)).acos()
}

/// The fixtures' five-bar at inputs `th1`, `th2`: C from the circles (B, b) and (D, c), B the
/// tip of crank `a` at the origin and D of crank `e` at (d, 0), on side `side` of B -> D (+1
/// left, -1 right), with the angles of B -> C and D -> C: `(cx, cy, phi2, phi3)`.
pub fn five_bar_joint(m: &FiveBar, th1: f64, th2: f64, side: f64) -> (f64, f64, f64, f64) {
    let (bx, by) = (m.a * th1.cos(), m.a * th1.sin());
    let (dx, dy) = (m.d + m.e * th2.cos(), m.e * th2.sin());
    let (cx, cy) = circle_point(bx, by, m.b, dx, dy, m.c, side);
    (cx, cy, (cy - by).atan2(cx - bx), (cy - dy).atan2(cx - dx))
}

/// The dead centres of an offset slider-crank (crank `r`, rod `l`, the guide `e` off the crank's
/// axis): the slider's distance from the axis along the guide where crank and rod are stretched,
/// `sqrt((l + r)^2 - e^2)`, and folded, `sqrt((l - r)^2 - e^2)`: paper 000's `X_F0` and `X_Fmin`.
pub fn dead_centres(l: f64, r: f64, e: f64) -> (f64, f64) {
    (((l + r).powi(2) - e * e).sqrt(), ((l - r).powi(2) - e * e).sqrt())
}

/// Paper 001's explicit formulas for the gear-lever drive at carrier angle `a` (u = z1/z3, L =
/// carrier, l = pin radius): `[phi, omega_r, eps_r, s, ds, x]`, the rocker angle, its velocity and
/// acceleration analogs, the pin's distance from O and its analog, and the pin's x.
pub fn gear_lever_explicit(big_l: f64, l: f64, u: f64, a: f64) -> [f64; 6] {
    let w = 1.0 - u;
    let x = big_l * a.sin() + l * (w * a).sin();
    let y = big_l * a.cos() + l * (w * a).cos();
    let xd = big_l * a.cos() + l * w * (w * a).cos();
    let yd = -big_l * a.sin() - l * w * (w * a).sin();
    let xdd = -big_l * a.sin() - l * w * w * (w * a).sin();
    let ydd = -big_l * a.cos() - l * w * w * (w * a).cos();
    let r2 = x * x + y * y;
    let omega_r = (xd * y - yd * x) / r2;
    let eps_r = ((xdd * y - ydd * x) * r2 - 2.0 * (xd * y - yd * x) * (xd * x + yd * y)) / (r2 * r2);
    // The paper's slip speed V = -(x'x + y'y)/sqrt(x^2 + y^2) is measured towards O; the
    // distance s = |OB| grows at ds/dalpha = -V.
    let v_slip = -(xd * x + yd * y) / r2.sqrt();
    let phi = x.atan2(y); // = arctan(x / y), on the right branch
    [phi, omega_r, eps_r, r2.sqrt(), -v_slip, x]
}

/// Newton until the residual is at rounding level (1e-14, below the default 1e-12) or the step
/// below 1e-16: a solve to compare other solves with.
pub fn newton_to_rounding() -> NewtonConfig {
    NewtonConfig::default().with_residual_tol(1e-14).with_step_tol(1e-16)
}

/// Newton until the residual is at the rounding floor of unit-size loops (1e-15), with the default
/// step tolerance: references for central differences, whose position errors the step divides.
pub fn newton_to_residual_floor() -> NewtonConfig {
    NewtonConfig::default().with_residual_tol(1e-15)
}

/// Newton without the residual test (tolerance 0): it stops when its step falls below the
/// default step tolerance, 1e-13 (1 + |q|), i.e. positions within ~5e-13; for finite
/// differences of positions, whose errors they divide by the step.
pub fn newton_to_default_step() -> NewtonConfig {
    NewtonConfig::default().with_residual_tol(0.0)
}

/// Newton with the residual test out of reach (1e-300) and the step down to 1e-15: positions
/// converged to rounding, for differences of positions divided by h or h^2, which the default
/// residual tolerance (1e-12) would dominate.
pub fn newton_to_fine_step() -> NewtonConfig {
    NewtonConfig::default().with_residual_tol(1e-300).with_step_tol(1e-15)
}

/// Panics unless `r` is the singular position of block 0 (`at` says where, in the message).
pub fn assert_singular_block_0<T: std::fmt::Debug>(r: Result<T, kinloop::Error>, at: &str) {
    match r {
        Err(e @ kinloop::Error::Singular { .. }) => {
            assert_eq!(e.location().and_then(|l| l.block.as_ref()).map(|(k, _)| *k), Some(0), "{at}: {e}");
        }
        other => panic!("{at}: {other:?}"),
    }
}
