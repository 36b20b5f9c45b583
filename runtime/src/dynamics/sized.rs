//! A mass model whose sizes are known at run time ([`MassModelBuf`], over [`Sizes`]), for
//! mechanisms read from text: the bodies and gravity as the compiled [`MassModel`] holds them,
//! the loads as where they act, their values computed by the caller (a run-time model
//! evaluates its load expressions on its own tape) and given to each evaluation. Its formulas
//! and checks are the compiled model's own (one implementation, in a private module).
//!
//! ```
//! use kinloop_runtime::dims::{KinBuf, Sizes};
//! use kinloop_runtime::dynamics::{Body, Coord, MassModelBuf, Rotation};
//!
//! // A crank of radius 0.1 turning with input 0, its centre of mass at the crank pin, a
//! // vertical force of 3 at the pin, in a hand-made state at phi = 0.
//! let r = 0.1;
//! let sizes = Sizes { n: 0, ni: 1, no: 2 };
//! let mut k = KinBuf::zeros(sizes);
//! k.out.copy_from_slice(&[r, 0.0]);
//! k.dout.copy_from_slice(&[0.0, r]);
//! k.d2out.copy_from_slice(&[-r, 0.0]);
//! let pin = [Coord::Output(0), Coord::Output(1)];
//! let model = MassModelBuf::new(sizes)
//!     .with_body(Body { name: "crank".into(), mass: 2.0, com: pin, inertia: 0.01, rotation: Rotation::Input(0) })?
//!     .with_force("push", pin)?;
//! let d = model.dynamics(&k, &[10.0], &[0.0, 3.0])?;
//! assert!((d.reduced_inertia() - (2.0 * r * r + 0.01)).abs() < 1e-15);
//! assert!((d.forces[0] - 3.0 * r).abs() < 1e-15);
//! # Ok::<(), kinloop_runtime::dynamics::DynamicsError>(())
//! ```
//!
//! [`MassModel`]: super::MassModel

use super::error::DynamicsError;
use super::eval::{
    Shaking, checked_centre, checked_drive_into, checked_forces, checked_inertia, checked_shaking, finite_values,
    force_value, torque_value,
};
use super::model::{Body, Point, Rotation, check_body, check_point, check_rotation};
use super::state::AnalogState;
use super::terms;
use crate::dims::Sizes;
use std::borrow::Cow;

/// Where a load of a [`MassModelBuf`] acts; its value is given to each evaluation.
#[derive(Clone, Debug, PartialEq)]
pub enum Applied {
    /// A force (two values, `F_x` and `F_y`) at a point.
    Force {
        /// Name used in error messages.
        name: Cow<'static, str>,
        /// The point of application.
        at: Point,
    },
    /// A torque (one value) on an angle.
    Torque {
        /// Name used in error messages.
        name: Cow<'static, str>,
        /// The angle it works on.
        on: Rotation,
    },
}

/// Bodies, loads and gravity of a mechanism whose sizes are known at run time; see the
/// [module documentation](self).
#[derive(Clone, Debug, PartialEq)]
pub struct MassModelBuf {
    sizes: Sizes,
    bodies: Vec<Body>,
    loads: Vec<Applied>,
    gravity: [f64; 2],
}

/// Mass matrix, velocity-product coefficients and generalised forces at one state, for `ni`
/// inputs known at run time (the compiled [`Dynamics`](super::Dynamics) with vectors).
#[derive(Clone, Debug, PartialEq)]
pub struct DynamicsBuf {
    /// `mass[i * ni + j] = M_ij`.
    pub mass: Vec<f64>,
    /// `gamma[(i * ni + j) * ni + k] = G_ijk`.
    pub gamma: Vec<f64>,
    /// The generalised forces `Q_i`.
    pub forces: Vec<f64>,
}

impl MassModelBuf {
    /// An empty model without gravity for a mechanism of sizes `sizes`.
    pub fn new(sizes: Sizes) -> Self {
        MassModelBuf { sizes, bodies: Vec::new(), loads: Vec::new(), gravity: [0.0; 2] }
    }

    /// The sizes of the states it reads.
    pub fn sizes(&self) -> Sizes {
        self.sizes
    }

    /// The bodies, in the order added.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The loads, in the order added.
    pub fn loads(&self) -> &[Applied] {
        &self.loads
    }

    /// The number of load values an evaluation takes: two per force, one per torque, in the
    /// order the loads were added.
    pub fn load_values(&self) -> usize {
        self.loads.iter().map(|l| if matches!(l, Applied::Force { .. }) { 2 } else { 1 }).sum()
    }

    /// The gravitational acceleration vector.
    pub fn gravity_vector(&self) -> [f64; 2] {
        self.gravity
    }

    /// Total mass of the bodies.
    pub fn total_mass(&self) -> f64 {
        self.bodies.iter().map(|b| b.mass).sum()
    }

    fn dims(&self) -> [usize; 3] {
        [self.sizes.n, self.sizes.ni, self.sizes.no]
    }

    /// Sets the gravitational acceleration (as [`MassModel::with_gravity`](super::MassModel::with_gravity)).
    pub fn with_gravity(mut self, g: [f64; 2]) -> Result<Self, DynamicsError> {
        finite_values("gravity", &g)?;
        self.gravity = g;
        Ok(self)
    }

    /// Adds a body after the checks of [`MassModel::with_body`](super::MassModel::with_body).
    pub fn with_body(mut self, body: Body) -> Result<Self, DynamicsError> {
        check_body(&body, self.total_mass(), self.dims())?;
        self.bodies.push(body);
        Ok(self)
    }

    /// Adds a force acting at `at`, its value given to each evaluation.
    pub fn with_force(mut self, name: impl Into<Cow<'static, str>>, at: Point) -> Result<Self, DynamicsError> {
        let name = name.into();
        check_point("load", &name, at, self.dims())?;
        self.loads.push(Applied::Force { name, at });
        Ok(self)
    }

    /// Adds a torque acting on `on`, its value given to each evaluation.
    pub fn with_torque(mut self, name: impl Into<Cow<'static, str>>, on: Rotation) -> Result<Self, DynamicsError> {
        let name = name.into();
        if on == Rotation::None {
            return Err(DynamicsError::TorqueOnSlider { name });
        }
        check_rotation("load", &name, on, self.dims())?;
        self.loads.push(Applied::Torque { name, on });
        Ok(self)
    }

    /// The state `k` and the input vectors of this model's sizes, else
    /// [`DynamicsError::SizeMismatch`].
    fn check_sizes<S: AnalogState + ?Sized>(
        &self,
        k: &S,
        vectors: &[(&'static str, usize)],
    ) -> Result<(), DynamicsError> {
        let s = self.sizes;
        let given = [
            ("inputs of the state", k.inputs().len(), s.ni),
            ("unknowns of the state", k.unknowns().len(), s.n),
            ("outputs of the state", k.outputs().len(), s.no),
        ];
        let vectors = vectors.iter().map(|&(what, len)| (what, len, s.ni));
        match given.into_iter().chain(vectors).find(|(_, given, expected)| given != expected) {
            Some((what, given, expected)) => Err(DynamicsError::SizeMismatch { what, expected, given }),
            None => Ok(()),
        }
    }

    /// [`MassModelBuf::dynamics`] into `out` (of `ni` inputs: no allocation).
    pub fn dynamics_into<S: AnalogState + ?Sized>(
        &self,
        k: &S,
        w: &[f64],
        loads: &[f64],
        out: &mut DynamicsBuf,
    ) -> Result<(), DynamicsError> {
        let ni = self.sizes.ni;
        self.check_sizes(k, &[("input speeds", w.len()), ("inputs of the result", out.forces.len())])?;
        out.check_shape(ni)?;
        if loads.len() != self.load_values() {
            return Err(DynamicsError::SizeMismatch {
                what: "load values",
                expected: self.load_values(),
                given: loads.len(),
            });
        }
        out.mass.fill(0.0);
        out.gamma.fill(0.0);
        out.forces.fill(0.0);
        terms::inertia_into(&self.bodies, k, ni, &mut out.mass, &mut out.gamma);
        let q = &mut out.forces;
        terms::gravity_into(&self.bodies, self.gravity, k, q);
        let mut values = loads.iter().copied();
        let mut next = || values.next().unwrap_or(f64::NAN);
        for load in &self.loads {
            match *load {
                Applied::Force { ref name, at } => {
                    let f = force_value(name, [next(), next()], k.inputs())?;
                    terms::force_into(k, at, f, q);
                }
                Applied::Torque { ref name, on } => {
                    let t = torque_value(name, next(), k.inputs())?;
                    terms::torque_into(k, on, t, q);
                }
            }
        }
        checked_forces(q, k, w)?;
        let finite = out.mass.iter().chain(&out.gamma).all(|v| v.is_finite());
        checked_inertia(finite, k)
    }

    /// Mass matrix, velocity-product coefficients and generalised forces at state `k`, input
    /// speeds `w` and load values `loads` (see [`MassModelBuf::load_values`]): the compiled
    /// [`MassModel::dynamics`](super::MassModel::dynamics), with its errors; a state or vector
    /// of other sizes is [`DynamicsError::SizeMismatch`].
    pub fn dynamics<S: AnalogState + ?Sized>(
        &self,
        k: &S,
        w: &[f64],
        loads: &[f64],
    ) -> Result<DynamicsBuf, DynamicsError> {
        let mut out = DynamicsBuf::zeros(self.sizes.ni);
        self.dynamics_into(k, w, loads, &mut out)?;
        Ok(out)
    }

    /// Shaking force and moment about `about` (the compiled
    /// [`MassModel::shaking`](super::MassModel::shaking)).
    pub fn shaking<S: AnalogState + ?Sized>(
        &self,
        k: &S,
        w: &[f64],
        eps: &[f64],
        about: [f64; 2],
    ) -> Result<Shaking, DynamicsError> {
        self.check_sizes(k, &[("input speeds", w.len()), ("input accelerations", eps.len())])?;
        checked_shaking(&self.bodies, k, w, eps, about)
    }

    /// Centre of mass of all bodies (the compiled
    /// [`MassModel::centre_of_mass`](super::MassModel::centre_of_mass)).
    pub fn centre_of_mass<S: AnalogState + ?Sized>(&self, k: &S) -> Result<[f64; 2], DynamicsError> {
        self.check_sizes(k, &[])?;
        checked_centre(&self.bodies, self.total_mass(), k)
    }
}

impl DynamicsBuf {
    /// Zeros for `ni` inputs.
    pub fn zeros(ni: usize) -> Self {
        DynamicsBuf { mass: vec![0.0; ni * ni], gamma: vec![0.0; ni * ni * ni], forces: vec![0.0; ni] }
    }

    /// The mass matrix and velocity-product coefficients of `ni` inputs (`ni * ni` and `ni^3`
    /// values: the fields are public, so a caller may have resized one), else
    /// [`DynamicsError::SizeMismatch`].
    fn check_shape(&self, ni: usize) -> Result<(), DynamicsError> {
        let shape = [
            ("inputs of the result", self.forces.len(), ni),
            ("mass matrix entries of the result", self.mass.len(), ni * ni),
            ("velocity-product coefficients of the result", self.gamma.len(), ni * ni * ni),
        ];
        match shape.into_iter().find(|(_, given, expected)| given != expected) {
            Some((what, given, expected)) => Err(DynamicsError::SizeMismatch { what, expected, given }),
            None => Ok(()),
        }
    }

    /// The reduced moment of inertia `J = M_00` (first input).
    pub fn reduced_inertia(&self) -> f64 {
        self.mass[0]
    }

    /// `dJ/dphi = 2 G_000` (first input, for a one-input mechanism).
    pub fn reduced_inertia_slope(&self) -> f64 {
        2.0 * self.gamma[0]
    }

    /// Kinetic energy `1/2 w^T M w` at input speeds `w` (plain arithmetic).
    pub fn kinetic_energy(&self, w: &[f64]) -> f64 {
        terms::kinetic_energy(&self.mass, w)
    }

    /// Inverse dynamics, checked (the compiled
    /// [`Dynamics::checked_drive`](super::Dynamics::checked_drive)): the driving forces
    /// `M eps + h(w) - Q` at inputs `x`, speeds `w` and accelerations `eps` into `tau`.
    pub fn checked_drive_into(&self, x: &[f64], w: &[f64], eps: &[f64], tau: &mut [f64]) -> Result<(), DynamicsError> {
        let ni = self.forces.len();
        self.check_shape(ni)?;
        for (what, given) in
            [("input speeds", w.len()), ("input accelerations", eps.len()), ("driving forces", tau.len())]
        {
            if given != ni {
                return Err(DynamicsError::SizeMismatch { what, expected: ni, given });
            }
        }
        checked_drive_into(&self.mass, &self.gamma, &self.forces, x, w, eps, tau)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dims::KinBuf;
    use crate::dynamics::Coord;

    fn crank() -> (MassModelBuf, KinBuf) {
        let sizes = Sizes { n: 1, ni: 1, no: 2 };
        let mut k = KinBuf::zeros(sizes);
        k.out.copy_from_slice(&[0.1, 0.0]);
        k.dout.copy_from_slice(&[0.0, 0.1]);
        k.d2out.copy_from_slice(&[-0.1, 0.0]);
        let pin = [Coord::Output(0), Coord::Output(1)];
        let body = Body { name: "crank".into(), mass: 2.0, com: pin, inertia: 0.01, rotation: Rotation::Input(0) };
        let m = MassModelBuf::new(sizes).with_body(body).unwrap().with_force("push", pin).unwrap();
        (m, k)
    }

    /// Bad sizes, indices, masses and load values are typed errors naming what is wrong.
    #[test]
    fn bad_input_is_a_typed_error() {
        let (m, k) = crank();
        assert_eq!(m.load_values(), 2);
        let e = m.dynamics(&k, &[1.0], &[0.0]).unwrap_err();
        assert_eq!(e, DynamicsError::SizeMismatch { what: "load values", expected: 2, given: 1 });
        let e = m.dynamics(&k, &[1.0, 2.0], &[0.0, 0.0]).unwrap_err();
        assert_eq!(e, DynamicsError::SizeMismatch { what: "input speeds", expected: 1, given: 2 });
        let other = KinBuf::zeros(Sizes { n: 2, ni: 1, no: 2 });
        let e = m.shaking(&other, &[1.0], &[0.0], [0.0; 2]).unwrap_err();
        assert_eq!(e, DynamicsError::SizeMismatch { what: "unknowns of the state", expected: 1, given: 2 });
        let e = m.dynamics(&k, &[1.0], &[f64::NAN, 0.0]).unwrap_err();
        assert!(matches!(&e, DynamicsError::NonFiniteLoad { name, .. } if name == "push"), "{e:?}");
        let e = m.clone().with_torque("t", Rotation::None).unwrap_err();
        assert_eq!(e, DynamicsError::TorqueOnSlider { name: "t".into() });
        let e = m.clone().with_force("f", [Coord::Output(2), Coord::Fixed(0.0)]).unwrap_err();
        assert!(matches!(e, DynamicsError::IndexOutOfRange { index: 2, len: 2, .. }), "{e:?}");
        let heavy =
            Body { name: "b".into(), mass: -1.0, com: [Coord::Fixed(0.0); 2], inertia: 0.0, rotation: Rotation::None };
        assert!(matches!(m.clone().with_body(heavy), Err(DynamicsError::BadMass { body, .. }) if body == "b"));
        let mut d = DynamicsBuf::zeros(1);
        let e = d.checked_drive_into(&[0.0], &[1.0], &[0.0], &mut [0.0; 2]).unwrap_err();
        assert_eq!(e, DynamicsError::SizeMismatch { what: "driving forces", expected: 1, given: 2 });
        // The public fields resized by a caller: a typed error, not a panic in the evaluation.
        let mut short = DynamicsBuf::zeros(1);
        short.mass.clear();
        let e = short.checked_drive_into(&[0.0], &[1.0], &[0.0], &mut [0.0]).unwrap_err();
        assert_eq!(e, DynamicsError::SizeMismatch { what: "mass matrix entries of the result", expected: 1, given: 0 });
        let e = m.dynamics_into(&k, &[1.0], &[0.0, 0.0], &mut short).unwrap_err();
        assert_eq!(e, DynamicsError::SizeMismatch { what: "mass matrix entries of the result", expected: 1, given: 0 });
        let mut short = DynamicsBuf::zeros(1);
        short.gamma.clear();
        let e = m.dynamics_into(&k, &[1.0], &[0.0, 0.0], &mut short).unwrap_err();
        let what = "velocity-product coefficients of the result";
        assert_eq!(e, DynamicsError::SizeMismatch { what, expected: 1, given: 0 });
        d.mass[0] = f64::INFINITY;
        assert!(matches!(
            d.checked_drive_into(&[0.0], &[1.0], &[0.0], &mut [0.0]),
            Err(DynamicsError::BadValue { .. })
        ));
    }

    /// A crank with its centre of mass at the pin, pushed upwards at the pin at phi = 0:
    /// `J = m r^2 + J_S`, `Q = F r`, the shaking force the centripetal `m r w^2` outwards and
    /// the kinetic energy `J w^2 / 2`.
    #[test]
    fn a_crank_s_dynamics_are_the_closed_forms() {
        let (m, k) = crank();
        let (r, w) = (0.1, 10.0);
        let d = m.dynamics(&k, &[w], &[0.0, 3.0]).unwrap();
        let j = 2.0 * r * r + 0.01;
        assert!((d.reduced_inertia() - j).abs() < 1e-15);
        assert_eq!(d.reduced_inertia_slope(), 0.0);
        assert!((d.forces[0] - 3.0 * r).abs() < 1e-15);
        assert!((d.kinetic_energy(&[w]) - 0.5 * j * w * w).abs() < 1e-13);
        let s = m.shaking(&k, &[w], &[0.0], [0.0, 0.0]).unwrap();
        assert!((s.force[0] - 2.0 * r * w * w).abs() < 1e-13 && s.force[1] == 0.0, "{s:?}");
        assert_eq!(m.centre_of_mass(&k).unwrap(), [0.1, 0.0]);
    }
}
