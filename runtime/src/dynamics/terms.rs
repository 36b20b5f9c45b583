//! The formulas of the dynamics (see [`eval`](super::eval)), written once over any kinematic
//! state ([`AnalogState`]) into slices of the inputs' sizes (`ni` inputs; a matrix by rows,
//! `m[i * ni + j]`, the velocity-product coefficients `g[(i * ni + j) * ni + k]`): a compiled
//! mass model writes them into its arrays, a run-time one ([`MassModelBuf`](super::MassModelBuf))
//! into its vectors, with the same operations in the same order.

use super::model::{Body, Point, Rotation};
use super::state::{AnalogState, d1, d2, value, w1, w2};

/// Shaking force and moment transmitted to the frame by the moving bodies' inertia.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shaking {
    /// `-sum m a_S`: the resultant of the inertia forces (equal to `-M_total a_G`).
    pub force: [f64; 2],
    /// `-sum ((r_S - O) x m a_S + J_S alpha)`: the moment of the inertia forces and couples
    /// about the frame point `O`.
    pub moment: f64,
}

/// Adds the bodies' mass matrix `M_ij` to `m` and their velocity-product coefficients `G_ijk`
/// to `g`.
#[inline]
pub(crate) fn inertia_into<S: AnalogState + ?Sized>(bodies: &[Body], k: &S, ni: usize, m: &mut [f64], g: &mut [f64]) {
    for b in bodies {
        let ([cx, cy], r) = (b.com, b.rotation);
        for i in 0..ni {
            let (mvx, mvy, jw) = (b.mass * d1(k, cx, i), b.mass * d1(k, cy, i), b.inertia * w1(k, r, i));
            for j in 0..ni {
                m[i * ni + j] += mvx * d1(k, cx, j) + mvy * d1(k, cy, j) + jw * w1(k, r, j);
                for l in 0..ni {
                    g[(i * ni + j) * ni + l] += mvx * d2(k, cx, j, l) + mvy * d2(k, cy, j, l) + jw * w2(k, r, j, l);
                }
            }
        }
    }
}

/// Adds the generalised forces of gravity `[gx, gy]` on the bodies to `q`.
#[inline]
pub(crate) fn gravity_into<S: AnalogState + ?Sized>(bodies: &[Body], [gx, gy]: [f64; 2], k: &S, q: &mut [f64]) {
    for b in bodies {
        let [cx, cy] = b.com;
        for (i, q) in q.iter_mut().enumerate() {
            *q += b.mass * (gx * d1(k, cx, i) + gy * d1(k, cy, i));
        }
    }
}

/// Adds the generalised forces of the force `[fx, fy]` at point `at` to `q`.
#[inline]
pub(crate) fn force_into<S: AnalogState + ?Sized>(k: &S, at: Point, [fx, fy]: [f64; 2], q: &mut [f64]) {
    for (i, q) in q.iter_mut().enumerate() {
        *q += fx * d1(k, at[0], i) + fy * d1(k, at[1], i);
    }
}

/// Adds the generalised forces of the torque `t` on the angle `on` to `q`.
#[inline]
pub(crate) fn torque_into<S: AnalogState + ?Sized>(k: &S, on: Rotation, t: f64, q: &mut [f64]) {
    for (i, q) in q.iter_mut().enumerate() {
        *q += t * w1(k, on, i);
    }
}

/// Velocity and acceleration of a quantity with analogs `d(i)`, `dd(i, j)` at input speeds `w`
/// and accelerations `e`: `sum d_i w_i` and `sum d_i e_i + sum dd_ij w_i w_j`.
#[inline(always)]
fn chain(d: impl Fn(usize) -> f64, dd: impl Fn(usize, usize) -> f64, w: &[f64], e: &[f64]) -> (f64, f64) {
    let (mut v, mut a) = (0.0, 0.0);
    for i in 0..w.len() {
        v += d(i) * w[i];
        a += d(i) * e[i];
        for j in 0..w.len() {
            a += dd(i, j) * w[i] * w[j];
        }
    }
    (v, a)
}

/// Shaking force and moment of the bodies about the frame point `about` at input speeds `w`
/// and accelerations `eps` (plain arithmetic; the callers check the result).
#[inline]
pub(crate) fn shaking<S: AnalogState + ?Sized>(
    bodies: &[Body],
    k: &S,
    w: &[f64],
    eps: &[f64],
    about: [f64; 2],
) -> Shaking {
    let mut s = Shaking { force: [0.0; 2], moment: 0.0 };
    for b in bodies {
        let ([cx, cy], r) = (b.com, b.rotation);
        let (x, y) = (value(k, cx), value(k, cy));
        let (_, ax) = chain(|i| d1(k, cx, i), |i, j| d2(k, cx, i, j), w, eps);
        let (_, ay) = chain(|i| d1(k, cy, i), |i, j| d2(k, cy, i, j), w, eps);
        let (_, alpha) = chain(|i| w1(k, r, i), |i, j| w2(k, r, i, j), w, eps);
        let (fx, fy) = (-b.mass * ax, -b.mass * ay);
        s.force[0] += fx;
        s.force[1] += fy;
        s.moment += (x - about[0]) * fy - (y - about[1]) * fx - b.inertia * alpha;
    }
    s
}

/// The centre of mass of the bodies of total mass `m > 0`, weighing each by its share of the
/// mass when the plain weighted sum overflows (a mean of finite coordinates is representable).
pub(crate) fn centre_of_mass<S: AnalogState + ?Sized>(bodies: &[Body], m: f64, k: &S) -> [f64; 2] {
    let (mut sx, mut sy) = (0.0, 0.0);
    for b in bodies {
        sx += b.mass * value(k, b.com[0]);
        sy += b.mass * value(k, b.com[1]);
    }
    let c = [sx / m, sy / m];
    if c.iter().all(|v| v.is_finite()) || k.non_finite().is_some() {
        return c;
    }
    let (mut cx, mut cy) = (0.0, 0.0);
    for b in bodies {
        cx += b.mass / m * value(k, b.com[0]);
        cy += b.mass / m * value(k, b.com[1]);
    }
    [cx, cy]
}

/// The velocity-product terms `h_i = sum_jk G_ijk w_j w_k` into `h`.
#[inline]
pub(crate) fn velocity_terms_into(gamma: &[f64], w: &[f64], h: &mut [f64]) {
    let ni = w.len();
    for i in 0..ni {
        h[i] = 0.0;
        for j in 0..ni {
            for k in 0..ni {
                h[i] += gamma[(i * ni + j) * ni + k] * w[j] * w[k];
            }
        }
    }
}

/// The driving forces `tau = M eps + h(w) - Q` into `tau` (plain arithmetic).
#[inline]
pub(crate) fn drive_into(mass: &[f64], gamma: &[f64], forces: &[f64], w: &[f64], eps: &[f64], tau: &mut [f64]) {
    let ni = w.len();
    velocity_terms_into(gamma, w, tau);
    for i in 0..ni {
        tau[i] -= forces[i];
        for j in 0..ni {
            tau[i] += mass[i * ni + j] * eps[j];
        }
    }
}

/// Kinetic energy `1/2 w^T M w` (plain arithmetic).
#[inline]
pub(crate) fn kinetic_energy(mass: &[f64], w: &[f64]) -> f64 {
    let ni = w.len();
    let mut t = 0.0;
    for i in 0..ni {
        for j in 0..ni {
            t += mass[i * ni + j] * w[i] * w[j];
        }
    }
    0.5 * t
}
