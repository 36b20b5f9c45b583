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
use super::model::{Body, Load, MassModel};
use super::state::AnalogState;
use super::terms;
pub use super::terms::Shaking;
use crate::kin::Kin;
use std::borrow::Cow;

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
        terms::velocity_terms_into(self.gamma.as_flattened().as_flattened(), w, &mut h);
        h
    }

    /// Inverse dynamics: the driving forces `tau = M eps + h(w) - Q` that give the input
    /// accelerations `eps` at input speeds `w` (for one input, the driving torque
    /// `J eps + 1/2 J' w^2 - Q`). Plain arithmetic: at speeds or accelerations so large that a
    /// force overflows, it is infinite; [`Dynamics::checked_drive`] makes that a typed error.
    pub fn drive(&self, w: &[f64; NI], eps: &[f64; NI]) -> [f64; NI] {
        let mut tau = [0.0; NI];
        let gamma = self.gamma.as_flattened().as_flattened();
        terms::drive_into(self.mass.as_flattened(), gamma, &self.forces, w, eps, &mut tau);
        tau
    }

    /// [`Dynamics::drive`] checked: a speed or acceleration that is not finite is
    /// [`DynamicsError::BadValue`], a driving force beyond the range of `f64` (huge speeds or
    /// accelerations) [`DynamicsError::Overflow`] at inputs `x`.
    pub fn checked_drive(&self, x: &[f64; NI], w: &[f64; NI], eps: &[f64; NI]) -> Result<[f64; NI], DynamicsError> {
        let mut tau = [0.0; NI];
        let gamma = self.gamma.as_flattened().as_flattened();
        checked_drive_into(self.mass.as_flattened(), gamma, &self.forces, x, w, eps, &mut tau)?;
        Ok(tau)
    }

    /// Whether the mass matrix, the velocity-product coefficients and the forces are finite.
    fn is_finite(&self) -> bool {
        let gamma = self.gamma.iter().flatten().flatten();
        self.mass.iter().flatten().chain(gamma).chain(&self.forces).all(|v| v.is_finite())
    }

    /// The coefficients finite (those of [`MassModel::dynamics`] are; fields set by hand may
    /// not be), else [`DynamicsError::BadValue`].
    fn check(&self) -> Result<(), DynamicsError> {
        finite_coefficients(self.mass.as_flattened(), self.gamma.as_flattened().as_flattened(), &self.forces)
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
                return Err(DynamicsError::SingularMass { x: x.to_vec(), pivot: d, names: Vec::new() });
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
            Err(DynamicsError::Overflow { what: "input accelerations", x: x.to_vec(), names: Vec::new() })
        }
    }
}

/// `values` all finite, else [`DynamicsError::BadValue`] naming the first that is not.
pub(crate) fn finite_values(what: &'static str, values: &[f64]) -> Result<(), DynamicsError> {
    match values.iter().find(|v| !v.is_finite()) {
        Some(&value) => Err(DynamicsError::BadValue { what, value, why: "must be finite" }),
        None => Ok(()),
    }
}

/// The mass matrix, velocity-product coefficients and forces finite (fields set by hand may
/// not be), else [`DynamicsError::BadValue`]; no allocation.
fn finite_coefficients(mass: &[f64], gamma: &[f64], forces: &[f64]) -> Result<(), DynamicsError> {
    match mass.iter().chain(gamma).chain(forces).find(|v| !v.is_finite()) {
        Some(&value) => {
            Err(DynamicsError::BadValue { what: "coefficient of the dynamics", value, why: "must be finite" })
        }
        None => Ok(()),
    }
}

/// Every number of state `k` finite (a state made by hand can hold anything), else
/// [`DynamicsError::BadValue`].
pub(crate) fn finite_state<S: AnalogState + ?Sized>(k: &S) -> Result<(), DynamicsError> {
    match k.non_finite() {
        Some(value) => Err(DynamicsError::BadValue { what: "kinematic state value", value, why: "must be finite" }),
        None => Ok(()),
    }
}

/// The driving forces `tau = M eps + h(w) - Q` checked: coefficients, speeds and
/// accelerations finite ([`DynamicsError::BadValue`]), the forces within the range of `f64`
/// ([`DynamicsError::Overflow`] at inputs `x`).
pub(crate) fn checked_drive_into(
    mass: &[f64],
    gamma: &[f64],
    forces: &[f64],
    x: &[f64],
    w: &[f64],
    eps: &[f64],
    tau: &mut [f64],
) -> Result<(), DynamicsError> {
    finite_coefficients(mass, gamma, forces)?;
    finite_values("input speed", w)?;
    finite_values("input acceleration", eps)?;
    terms::drive_into(mass, gamma, forces, w, eps, tau);
    if tau.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(DynamicsError::Overflow { what: "driving force", x: x.to_vec(), names: Vec::new() })
    }
}

/// A force's value checked finite, else [`DynamicsError::NonFiniteLoad`] at inputs `x`.
// A `&Cow` (not `&str`): the error clones it, which keeps a compiled mechanism's borrowed
// name borrowed; the usual, finite call allocates nothing.
#[allow(clippy::ptr_arg)]
pub(crate) fn force_value(name: &Cow<'static, str>, f: [f64; 2], x: &[f64]) -> Result<[f64; 2], DynamicsError> {
    match f.iter().find(|v| !v.is_finite()) {
        Some(&value) => {
            Err(DynamicsError::NonFiniteLoad { name: name.clone(), value, x: x.to_vec(), names: Vec::new() })
        }
        None => Ok(f),
    }
}

/// A torque's value checked finite, else [`DynamicsError::NonFiniteLoad`] at inputs `x`.
#[allow(clippy::ptr_arg)]
pub(crate) fn torque_value(name: &Cow<'static, str>, t: f64, x: &[f64]) -> Result<f64, DynamicsError> {
    if t.is_finite() {
        Ok(t)
    } else {
        Err(DynamicsError::NonFiniteLoad { name: name.clone(), value: t, x: x.to_vec(), names: Vec::new() })
    }
}

/// Generalised forces `q` computed from finite loads, checked: a value that is not finite comes
/// from a state value or a speed that is not finite ([`DynamicsError::BadValue`]) or else from
/// an overflow.
pub(crate) fn checked_forces<S: AnalogState + ?Sized>(q: &[f64], k: &S, w: &[f64]) -> Result<(), DynamicsError> {
    if q.iter().all(|v| v.is_finite()) {
        return Ok(());
    }
    finite_state(k)?;
    finite_values("input speed", w)?;
    Err(DynamicsError::Overflow { what: "generalised forces", x: k.inputs().to_vec(), names: Vec::new() })
}

/// A mass matrix and velocity-product coefficients checked finite (see [`checked_forces`]).
pub(crate) fn checked_inertia<S: AnalogState + ?Sized>(finite: bool, k: &S) -> Result<(), DynamicsError> {
    if finite {
        return Ok(());
    }
    finite_state(k)?;
    Err(DynamicsError::Overflow {
        what: "mass matrix or velocity-product coefficients",
        x: k.inputs().to_vec(),
        names: Vec::new(),
    })
}

/// The centre of mass of `bodies` of total mass `m`, checked (see [`MassModel::centre_of_mass`]).
pub(crate) fn checked_centre<S: AnalogState + ?Sized>(
    bodies: &[Body],
    m: f64,
    k: &S,
) -> Result<[f64; 2], DynamicsError> {
    if m <= 0.0 {
        return Err(DynamicsError::BadValue {
            what: "total mass",
            value: m,
            why: "must be positive for a centre of mass",
        });
    }
    let c = terms::centre_of_mass(bodies, m, k);
    if !c.iter().all(|v| v.is_finite()) {
        finite_state(k)?;
    }
    Ok(c)
}

/// The shaking force and moment of `bodies`, checked (see [`MassModel::shaking`]).
pub(crate) fn checked_shaking<S: AnalogState + ?Sized>(
    bodies: &[Body],
    k: &S,
    w: &[f64],
    eps: &[f64],
    about: [f64; 2],
) -> Result<Shaking, DynamicsError> {
    finite_values("input speed", w)?;
    finite_values("input acceleration", eps)?;
    finite_values("moment centre", &about)?;
    let s = terms::shaking(bodies, k, w, eps, about);
    if s.force.iter().all(|f| f.is_finite()) && s.moment.is_finite() {
        return Ok(s);
    }
    finite_state(k)?;
    Err(DynamicsError::Overflow { what: "shaking force or moment", x: k.inputs().to_vec(), names: Vec::new() })
}

impl<const N: usize, const NI: usize, const NO: usize> MassModel<N, NI, NO> {
    /// Mass matrix and velocity-product coefficients at state `k` (no loads evaluated).
    pub fn inertia(&self, k: &Kin<N, NI, NO>) -> ([[f64; NI]; NI], [[[f64; NI]; NI]; NI]) {
        let mut m = [[0.0; NI]; NI];
        let mut g = [[[0.0; NI]; NI]; NI];
        terms::inertia_into(&self.bodies, k, NI, m.as_flattened_mut(), g.as_flattened_mut().as_flattened_mut());
        (m, g)
    }

    /// Generalised forces `Q_i` of the loads and gravity at state `k` and input speeds `w`.
    /// A load law returning NaN or infinity is an error.
    pub fn generalized_forces(&self, k: &Kin<N, NI, NO>, w: &[f64; NI]) -> Result<[f64; NI], DynamicsError> {
        let mut q = [0.0; NI];
        terms::gravity_into(&self.bodies, self.gravity, k, &mut q);
        for load in &self.loads {
            match load {
                Load::Force { name, at, law } => {
                    let f = force_value(name, law(k, w), &k.x)?;
                    terms::force_into(k, *at, f, &mut q);
                }
                Load::Torque { name, on, law } => {
                    let t = torque_value(name, law(k, w), &k.x)?;
                    terms::torque_into(k, *on, t, &mut q);
                }
            }
        }
        checked_forces(&q, k, w)?;
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
        checked_inertia(d.is_finite(), k)?;
        Ok(d)
    }

    /// Kinetic energy `1/2 w^T M w` at input speeds `w` (plain arithmetic: infinite when it
    /// overflows, and NaN for a speed or a state value that is not finite).
    pub fn kinetic_energy(&self, k: &Kin<N, NI, NO>, w: &[f64; NI]) -> f64 {
        let (m, _) = self.inertia(k);
        terms::kinetic_energy(m.as_flattened(), w)
    }

    /// Centre of mass of all bodies. A model without mass has none
    /// ([`DynamicsError::BadValue`]); a state value that is not finite is
    /// [`DynamicsError::BadValue`] too.
    pub fn centre_of_mass(&self, k: &Kin<N, NI, NO>) -> Result<[f64; 2], DynamicsError> {
        checked_centre(&self.bodies, self.total_mass(), k)
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
        checked_shaking(&self.bodies, k, w, eps, about)
    }
}
