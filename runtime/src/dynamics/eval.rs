//! The dynamic quantities at one kinematic state, exactly from the analogs.
//!
//! With `v_Si = d r_S / d x_i`, `a_Sij = d2 r_S / d x_i d x_j` (the centre of mass's velocity and
//! acceleration analogs) and `w_i`, `e_ij` the same for the body's angle, the kinetic energy is
//! `T = 1/2 sum_ij M_ij x'_i x'_j` with the mass matrix
//!
//! ```text
//! M_ij = sum_bodies m v_Si . v_Sj + J_S w_i w_j
//! ```
//!
//! and Lagrange's equations read `sum_j M_ij x''_j + sum_jk G_ijk x'_j x'_k = tau_i + Q_i` with
//! `G_ijk = sum m v_Si . a_Sjk + J_S w_i e_jk` (for a holonomic, scleronomic chain
//! `d/dt dT/dx'_i - dT/dx_i = sum m v_Si . a_S + J_S w_i alpha`). For one input this is
//! `J(phi) phi'' + 1/2 J'(phi) phi'^2 = M + Q` with the reduced moment of inertia `J = M_00`
//! and `dJ/dphi = 2 G_000`. The generalised forces come from virtual power:
//! `Q_i = sum F . v_Pi + T w_i + sum m g . v_Si`.

use super::error::DynamicsError;
use super::model::{Coord, Load, MassModel, Rotation};
use crate::kin::Kin;

/// Mass matrix, velocity-product coefficients and generalised forces at one state; see the
/// [module documentation](self).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dynamics<const NI: usize> {
    /// The mass matrix `M_ij` (the reduced moment of inertia `J` for one input).
    pub mass: [[f64; NI]; NI],
    /// `G_ijk = sum m v_Si . a_Sjk + J_S w_i e_jk` (for one input, `1/2 dJ/dphi`).
    pub gamma: [[[f64; NI]; NI]; NI],
    /// Generalised forces of the loads and gravity, `Q_i`.
    pub forces: [f64; NI],
}

/// Shaking force and moment transmitted to the frame by the moving bodies' inertia.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shaking {
    /// `-sum m a_S`: the resultant of the inertia forces (equal to `-M_total a_G`).
    pub force: [f64; 2],
    /// `-sum ((r_S - O) x m a_S + J_S alpha)`: the moment of the inertia forces and couples
    /// about the frame point `O`.
    pub moment: f64,
}

impl<const NI: usize> Dynamics<NI> {
    /// The reduced moment of inertia `J = M_00` (first input).
    pub fn reduced_inertia(&self) -> f64 {
        self.mass[0][0]
    }

    /// `dJ/dphi = 2 G_000` (first input, for a one-input mechanism).
    pub fn reduced_inertia_slope(&self) -> f64 {
        2.0 * self.gamma[0][0][0]
    }

    /// The velocity-product terms `h_i = sum_jk G_ijk w_j w_k` at input speeds `w`.
    pub fn velocity_terms(&self, w: &[f64; NI]) -> [f64; NI] {
        let mut h = [0.0; NI];
        for i in 0..NI {
            for j in 0..NI {
                for k in 0..NI {
                    h[i] += self.gamma[i][j][k] * w[j] * w[k];
                }
            }
        }
        h
    }

    /// Inverse dynamics: the driving forces `tau = M eps + h(w) - Q` that give the input
    /// accelerations `eps` at input speeds `w` (for one input, the driving torque
    /// `J eps + 1/2 J' w^2 - Q`). Plain arithmetic: at speeds or accelerations so large that a
    /// force overflows, it is infinite; [`Dynamics::checked_drive`] makes that a typed error.
    pub fn drive(&self, w: &[f64; NI], eps: &[f64; NI]) -> [f64; NI] {
        let h = self.velocity_terms(w);
        let mut tau = [0.0; NI];
        for i in 0..NI {
            tau[i] = h[i] - self.forces[i];
            for j in 0..NI {
                tau[i] += self.mass[i][j] * eps[j];
            }
        }
        tau
    }

    /// [`Dynamics::drive`] checked: a speed or acceleration that is not finite is
    /// [`DynamicsError::BadValue`], a driving force beyond the range of `f64` (huge speeds or
    /// accelerations) [`DynamicsError::Overflow`] at inputs `x`.
    pub fn checked_drive(&self, x: &[f64; NI], w: &[f64; NI], eps: &[f64; NI]) -> Result<[f64; NI], DynamicsError> {
        self.check()?;
        finite_values("input speed", w)?;
        finite_values("input acceleration", eps)?;
        let tau = self.drive(w, eps);
        if tau.iter().all(|v| v.is_finite()) {
            Ok(tau)
        } else {
            Err(DynamicsError::Overflow { what: "driving force", x: x.to_vec() })
        }
    }

    /// Whether the mass matrix, the velocity-product coefficients and the forces are finite.
    fn is_finite(&self) -> bool {
        let gamma = self.gamma.iter().flatten().flatten();
        self.mass.iter().flatten().chain(gamma).chain(&self.forces).all(|v| v.is_finite())
    }

    /// The coefficients finite (those of [`MassModel::dynamics`] are; fields set by hand may
    /// not be), else [`DynamicsError::BadValue`].
    fn check(&self) -> Result<(), DynamicsError> {
        let gamma = self.gamma.iter().flatten().flatten();
        let all: Vec<f64> = self.mass.iter().flatten().chain(gamma).chain(&self.forces).copied().collect();
        finite_values("coefficient of the dynamics", &all)
    }

    /// Forward dynamics: the input accelerations under driving forces `tau` at speeds `w`,
    /// from `M eps = tau + Q - h` by Cholesky factorisation. Fails with
    /// [`DynamicsError::SingularMass`] (carrying `x`) when `M` is not positive definite, with
    /// [`DynamicsError::BadValue`] for a speed or force that is not finite and with
    /// [`DynamicsError::Overflow`] when the accelerations are beyond the range of `f64`.
    pub fn accelerations(&self, x: &[f64; NI], w: &[f64; NI], tau: &[f64; NI]) -> Result<[f64; NI], DynamicsError> {
        self.check()?;
        finite_values("input speed", w)?;
        finite_values("driving force", tau)?;
        let h = self.velocity_terms(w);
        let mut b = [0.0; NI];
        for i in 0..NI {
            b[i] = tau[i] + self.forces[i] - h[i];
        }
        // Cholesky M = L L^T, in place in the lower triangle; pivots relative to the diagonal.
        let mut l = self.mass;
        for j in 0..NI {
            let mut d = l[j][j];
            for k in 0..j {
                d -= l[j][k] * l[j][k];
            }
            let scale = self.mass[j][j].abs();
            if !d.is_finite() || d <= 1e-13 * scale {
                return Err(DynamicsError::SingularMass { x: x.to_vec(), pivot: d });
            }
            let d = d.sqrt();
            l[j][j] = d;
            for i in j + 1..NI {
                let mut s = l[i][j];
                for k in 0..j {
                    s -= l[i][k] * l[j][k];
                }
                l[i][j] = s / d;
            }
        }
        for i in 0..NI {
            for k in 0..i {
                b[i] -= l[i][k] * b[k];
            }
            b[i] /= l[i][i];
        }
        for i in (0..NI).rev() {
            for k in i + 1..NI {
                b[i] -= l[k][i] * b[k];
            }
            b[i] /= l[i][i];
        }
        if b.iter().all(|v| v.is_finite()) {
            Ok(b)
        } else {
            Err(DynamicsError::Overflow { what: "input accelerations", x: x.to_vec() })
        }
    }
}

/// `values` all finite, else [`DynamicsError::BadValue`] naming the first that is not.
fn finite_values(what: &'static str, values: &[f64]) -> Result<(), DynamicsError> {
    match values.iter().find(|v| !v.is_finite()) {
        Some(&value) => Err(DynamicsError::BadValue { what, value, why: "must be finite" }),
        None => Ok(()),
    }
}

/// Every number of state `k` finite (a state made by hand can hold anything), else
/// [`DynamicsError::BadValue`].
fn finite_state<const N: usize, const NI: usize, const NO: usize>(k: &Kin<N, NI, NO>) -> Result<(), DynamicsError> {
    let analogs = k.dq.iter().flatten().chain(k.d2q.iter().flatten().flatten());
    let outputs = k.dout.iter().flatten().chain(k.d2out.iter().flatten().flatten());
    let all: Vec<f64> = k.x.iter().chain(&k.q).chain(analogs).chain(&k.out).chain(outputs).copied().collect();
    finite_values("kinematic state value", &all)
}

/// Value and analogs of a coordinate.
#[inline]
fn coord<const N: usize, const NI: usize, const NO: usize>(
    k: &Kin<N, NI, NO>,
    c: Coord,
) -> (f64, [f64; NI], [[f64; NI]; NI]) {
    match c {
        Coord::Output(o) => (k.out[o], k.dout[o], k.d2out[o]),
        Coord::Unknown(u) => (k.q[u], k.dq[u], k.d2q[u]),
        Coord::Fixed(v) => (v, [0.0; NI], [[0.0; NI]; NI]),
    }
}

/// Analogs `(w_i, e_ij)` of a body's angle.
#[inline]
fn rotation_analogs<const N: usize, const NI: usize, const NO: usize>(
    k: &Kin<N, NI, NO>,
    r: Rotation,
) -> ([f64; NI], [[f64; NI]; NI]) {
    match r {
        Rotation::Unknown(u) => (k.dq[u], k.d2q[u]),
        Rotation::Input(i) => {
            let mut w = [0.0; NI];
            w[i] = 1.0;
            (w, [[0.0; NI]; NI])
        }
        Rotation::None => ([0.0; NI], [[0.0; NI]; NI]),
    }
}

impl<const N: usize, const NI: usize, const NO: usize> MassModel<N, NI, NO> {
    /// Mass matrix and velocity-product coefficients at state `k` (no loads evaluated).
    pub fn inertia(&self, k: &Kin<N, NI, NO>) -> ([[f64; NI]; NI], [[[f64; NI]; NI]; NI]) {
        let mut m = [[0.0; NI]; NI];
        let mut g = [[[0.0; NI]; NI]; NI];
        for b in &self.bodies {
            let (_, vx, ax) = coord(k, b.com[0]);
            let (_, vy, ay) = coord(k, b.com[1]);
            let (w, e) = rotation_analogs(k, b.rotation);
            for i in 0..NI {
                let (mvx, mvy, jw) = (b.mass * vx[i], b.mass * vy[i], b.inertia * w[i]);
                for j in 0..NI {
                    m[i][j] += mvx * vx[j] + mvy * vy[j] + jw * w[j];
                    for l in 0..NI {
                        g[i][j][l] += mvx * ax[j][l] + mvy * ay[j][l] + jw * e[j][l];
                    }
                }
            }
        }
        (m, g)
    }

    /// Generalised forces `Q_i` of the loads and gravity at state `k` and input speeds `w`.
    /// A load law returning NaN or infinity is an error.
    pub fn generalized_forces(&self, k: &Kin<N, NI, NO>, w: &[f64; NI]) -> Result<[f64; NI], DynamicsError> {
        let mut q = [0.0; NI];
        let [gx, gy] = self.gravity;
        for b in &self.bodies {
            let (_, vx, _) = coord(k, b.com[0]);
            let (_, vy, _) = coord(k, b.com[1]);
            for i in 0..NI {
                q[i] += b.mass * (gx * vx[i] + gy * vy[i]);
            }
        }
        for load in &self.loads {
            match load {
                Load::Force { name, at, law } => {
                    let [fx, fy] = law(k, w);
                    if !(fx.is_finite() && fy.is_finite()) {
                        let value = if fx.is_finite() { fy } else { fx };
                        return Err(DynamicsError::NonFiniteLoad { name, value, x: k.x.to_vec() });
                    }
                    let (_, vx, _) = coord(k, at[0]);
                    let (_, vy, _) = coord(k, at[1]);
                    for i in 0..NI {
                        q[i] += fx * vx[i] + fy * vy[i];
                    }
                }
                Load::Torque { name, on, law } => {
                    let t = law(k, w);
                    if !t.is_finite() {
                        return Err(DynamicsError::NonFiniteLoad { name, value: t, x: k.x.to_vec() });
                    }
                    let (rw, _) = rotation_analogs(k, *on);
                    for i in 0..NI {
                        q[i] += t * rw[i];
                    }
                }
            }
        }
        if !q.iter().all(|v| v.is_finite()) {
            finite_state(k)?;
            finite_values("input speed", w)?;
            return Err(DynamicsError::Overflow { what: "generalised forces", x: k.x.to_vec() });
        }
        Ok(q)
    }

    /// Mass matrix, velocity-product coefficients and generalised forces at state `k` and
    /// input speeds `w`: one dynamics evaluation. A state value that is not finite is
    /// [`DynamicsError::BadValue`]; a result beyond the range of `f64` (masses and analogs so
    /// large that their products overflow) is [`DynamicsError::Overflow`].
    #[inline]
    pub fn dynamics(&self, k: &Kin<N, NI, NO>, w: &[f64; NI]) -> Result<Dynamics<NI>, DynamicsError> {
        let (mass, gamma) = self.inertia(k);
        let d = Dynamics { mass, gamma, forces: self.generalized_forces(k, w)? };
        if !d.is_finite() {
            finite_state(k)?;
            return Err(DynamicsError::Overflow {
                what: "mass matrix or velocity-product coefficients",
                x: k.x.to_vec(),
            });
        }
        Ok(d)
    }

    /// Kinetic energy `1/2 w^T M w` at input speeds `w` (plain arithmetic: infinite when it
    /// overflows, and NaN for a speed or a state value that is not finite).
    pub fn kinetic_energy(&self, k: &Kin<N, NI, NO>, w: &[f64; NI]) -> f64 {
        let (m, _) = self.inertia(k);
        let mut t = 0.0;
        for i in 0..NI {
            for j in 0..NI {
                t += m[i][j] * w[i] * w[j];
            }
        }
        0.5 * t
    }

    /// Centre of mass of all bodies. A model without mass has none
    /// ([`DynamicsError::BadValue`]); a state value that is not finite is
    /// [`DynamicsError::BadValue`] too.
    pub fn centre_of_mass(&self, k: &Kin<N, NI, NO>) -> Result<[f64; 2], DynamicsError> {
        let m = self.total_mass();
        if m <= 0.0 {
            return Err(DynamicsError::BadValue {
                what: "total mass",
                value: m,
                why: "must be positive for a centre of mass",
            });
        }
        let (mut sx, mut sy) = (0.0, 0.0);
        for b in &self.bodies {
            sx += b.mass * coord(k, b.com[0]).0;
            sy += b.mass * coord(k, b.com[1]).0;
        }
        let c = [sx / m, sy / m];
        if c.iter().all(|v| v.is_finite()) {
            return Ok(c);
        }
        finite_state(k)?;
        // A mean of finite coordinates is representable: weigh each by its share of the mass
        // (at most 1), so that no product or sum overflows.
        let (mut cx, mut cy) = (0.0, 0.0);
        for b in &self.bodies {
            cx += b.mass / m * coord(k, b.com[0]).0;
            cy += b.mass / m * coord(k, b.com[1]).0;
        }
        Ok([cx, cy])
    }

    /// Shaking force and moment about the frame point `about` at input speeds `w` and input
    /// accelerations `eps` (see [`Shaking`]). Values that are not finite are
    /// [`DynamicsError::BadValue`]; a force or moment beyond the range of `f64` is
    /// [`DynamicsError::Overflow`].
    pub fn shaking(
        &self,
        k: &Kin<N, NI, NO>,
        w: &[f64; NI],
        eps: &[f64; NI],
        about: [f64; 2],
    ) -> Result<Shaking, DynamicsError> {
        finite_values("input speed", w)?;
        finite_values("input acceleration", eps)?;
        finite_values("moment centre", &about)?;
        let mut s = Shaking { force: [0.0; 2], moment: 0.0 };
        for b in &self.bodies {
            let (x, vx, ax) = coord(k, b.com[0]);
            let (y, vy, ay) = coord(k, b.com[1]);
            let (_, ax) = chain(&vx, &ax, w, eps);
            let (_, ay) = chain(&vy, &ay, w, eps);
            let (rw, re) = rotation_analogs(k, b.rotation);
            let (_, alpha) = chain(&rw, &re, w, eps);
            let (fx, fy) = (-b.mass * ax, -b.mass * ay);
            s.force[0] += fx;
            s.force[1] += fy;
            s.moment += (x - about[0]) * fy - (y - about[1]) * fx - b.inertia * alpha;
        }
        if s.force.iter().all(|f| f.is_finite()) && s.moment.is_finite() {
            return Ok(s);
        }
        finite_state(k)?;
        Err(DynamicsError::Overflow { what: "shaking force or moment", x: k.x.to_vec() })
    }
}

/// Velocity and acceleration of a coordinate from its analogs: `sum d_i w_i` and
/// `sum d_i e_i + sum d2_ij w_i w_j`.
#[inline]
fn chain<const NI: usize>(d: &[f64; NI], d2: &[[f64; NI]; NI], w: &[f64; NI], e: &[f64; NI]) -> (f64, f64) {
    let (mut v, mut a) = (0.0, 0.0);
    for i in 0..NI {
        v += d[i] * w[i];
        a += d[i] * e[i];
        for j in 0..NI {
            a += d2[i][j] * w[i] * w[j];
        }
    }
    (v, a)
}
