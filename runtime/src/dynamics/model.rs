//! The mass model of a machine: rigid bodies, applied loads and gravity, all referring to the
//! kinematic state ([`Kin`]) by index, so that one model serves every input value.

use super::error::DynamicsError;
use crate::kin::Kin;
use std::borrow::Cow;

/// The angle a body rotates with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rotation {
    /// Unknown `u` of the mechanism (a rod angle).
    Unknown(usize),
    /// Input `i` (a crank driven directly; an angle `phi + const` rotates with `phi`).
    Input(usize),
    /// The body translates (a slider): it has no angular velocity.
    None,
}

/// A coordinate (x or y) of a point, read from the kinematic state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Coord {
    /// Output column `c` (a declared `point p` gives the columns `p.x`, `p.y`).
    Output(usize),
    /// Unknown `u` (a slider's coordinate).
    Unknown(usize),
    /// A constant (a point moving along a fixed line, or a centre of mass on a frame axis).
    Fixed(f64),
}

/// A point `[x, y]` read from the kinematic state.
pub type Point = [Coord; 2];

/// A rigid body: its mass, centre of mass, and moment of inertia about the centre of mass.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Name used in error messages (a compiled mechanism's borrowed, a run-time model's owned).
    pub name: Cow<'static, str>,
    /// Mass (not negative).
    pub mass: f64,
    /// The centre of mass.
    pub com: Point,
    /// Moment of inertia about the centre of mass (not negative).
    pub inertia: f64,
    /// The angle the body rotates with.
    pub rotation: Rotation,
}

/// A force law: the force `(F_x, F_y)` from the state and the input speeds.
pub type ForceLaw<const N: usize, const NI: usize, const NO: usize> =
    Box<dyn Fn(&Kin<N, NI, NO>, &[f64; NI]) -> [f64; 2] + Send + Sync>;
/// A torque law: the torque (counter-clockwise positive) from the state and the input speeds.
pub type TorqueLaw<const N: usize, const NI: usize, const NO: usize> =
    Box<dyn Fn(&Kin<N, NI, NO>, &[f64; NI]) -> f64 + Send + Sync>;

/// An applied load: a force at a point or a torque on an angle.
pub enum Load<const N: usize, const NI: usize, const NO: usize> {
    /// A force applied at the point `at`.
    Force {
        /// Name used in error messages.
        name: Cow<'static, str>,
        /// The point of application.
        at: Point,
        /// The force.
        law: ForceLaw<N, NI, NO>,
    },
    /// A torque on a body rotating with `on` (its reaction acts on the frame).
    Torque {
        /// Name used in error messages.
        name: Cow<'static, str>,
        /// The angle the torque works on.
        on: Rotation,
        /// The torque.
        law: TorqueLaw<N, NI, NO>,
    },
}

/// The load's name and where it acts; its law, a closure, is not shown.
impl<const N: usize, const NI: usize, const NO: usize> std::fmt::Debug for Load<N, NI, NO> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Load::Force { name, at, .. } => {
                f.debug_struct("Force").field("name", name).field("at", at).finish_non_exhaustive()
            }
            Load::Torque { name, on, .. } => {
                f.debug_struct("Torque").field("name", name).field("on", on).finish_non_exhaustive()
            }
        }
    }
}

impl<const N: usize, const NI: usize, const NO: usize> Load<N, NI, NO> {
    /// The load's name.
    pub fn name(&self) -> &str {
        match self {
            Load::Force { name, .. } | Load::Torque { name, .. } => name,
        }
    }
}

/// Bodies, loads and gravity of a mechanism with `N` unknowns, `NI` inputs and `NO` output
/// columns. Every index is checked when the part is added; see
/// [`dynamics`](crate::dynamics) for an example.
#[derive(Debug)]
pub struct MassModel<const N: usize, const NI: usize, const NO: usize> {
    pub(crate) bodies: Vec<Body>,
    pub(crate) loads: Vec<Load<N, NI, NO>>,
    pub(crate) gravity: [f64; 2],
}

impl<const N: usize, const NI: usize, const NO: usize> Default for MassModel<N, NI, NO> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize, const NI: usize, const NO: usize> MassModel<N, NI, NO> {
    /// An empty model without gravity.
    pub fn new() -> Self {
        MassModel { bodies: Vec::new(), loads: Vec::new(), gravity: [0.0; 2] }
    }

    /// The bodies, in the order added.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The loads, in the order added.
    pub fn loads(&self) -> &[Load<N, NI, NO>] {
        &self.loads
    }

    /// The gravitational acceleration vector.
    pub fn gravity_vector(&self) -> [f64; 2] {
        self.gravity
    }

    /// Total mass of the bodies (always finite: [`MassModel::with_body`] refuses a body that
    /// would make it overflow).
    pub fn total_mass(&self) -> f64 {
        self.bodies.iter().map(|b| b.mass).sum()
    }

    /// Sets the gravitational acceleration (e.g. `[0.0, -9.81]` with y up, in the model's units).
    pub fn with_gravity(mut self, g: [f64; 2]) -> Result<Self, DynamicsError> {
        for v in g {
            if !v.is_finite() {
                return Err(DynamicsError::BadValue { what: "gravity", value: v, why: "must be finite" });
            }
        }
        self.gravity = g;
        Ok(self)
    }

    /// Adds a body after checking its mass, inertia and indices, and that the total mass stays
    /// within the range of `f64` ([`DynamicsError::Overflow`] otherwise).
    pub fn with_body(mut self, body: Body) -> Result<Self, DynamicsError> {
        check_body(&body, self.total_mass(), [N, NI, NO])?;
        self.bodies.push(body);
        Ok(self)
    }

    /// Adds a force law applied at the point `at`.
    pub fn with_force(
        mut self,
        name: impl Into<Cow<'static, str>>,
        at: Point,
        law: impl Fn(&Kin<N, NI, NO>, &[f64; NI]) -> [f64; 2] + Send + Sync + 'static,
    ) -> Result<Self, DynamicsError> {
        let name = name.into();
        check_point("load", &name, at, [N, NI, NO])?;
        self.loads.push(Load::Force { name, at, law: Box::new(law) });
        Ok(self)
    }

    /// Adds a constant force applied at the point `at`.
    pub fn with_constant_force(
        self,
        name: impl Into<Cow<'static, str>>,
        at: Point,
        f: [f64; 2],
    ) -> Result<Self, DynamicsError> {
        for v in f {
            if !v.is_finite() {
                return Err(DynamicsError::BadValue { what: "force", value: v, why: "must be finite" });
            }
        }
        self.with_force(name, at, move |_, _| f)
    }

    /// Adds a torque law acting on the angle `on`.
    pub fn with_torque(
        mut self,
        name: impl Into<Cow<'static, str>>,
        on: Rotation,
        law: impl Fn(&Kin<N, NI, NO>, &[f64; NI]) -> f64 + Send + Sync + 'static,
    ) -> Result<Self, DynamicsError> {
        let name = name.into();
        if on == Rotation::None {
            return Err(DynamicsError::TorqueOnSlider { name });
        }
        check_rotation("load", &name, on, [N, NI, NO])?;
        self.loads.push(Load::Torque { name, on, law: Box::new(law) });
        Ok(self)
    }

    /// Adds a constant torque acting on the angle `on`.
    pub fn with_constant_torque(
        self,
        name: impl Into<Cow<'static, str>>,
        on: Rotation,
        t: f64,
    ) -> Result<Self, DynamicsError> {
        if !t.is_finite() {
            return Err(DynamicsError::BadValue { what: "torque", value: t, why: "must be finite" });
        }
        self.with_torque(name, on, move |_, _| t)
    }
}

/// A body's mass, inertia and indices checked against the sizes `[n, ni, no]`, and the total
/// mass `total` of the bodies before it kept within the range of `f64`.
pub(crate) fn check_body(body: &Body, total: f64, sizes: [usize; 3]) -> Result<(), DynamicsError> {
    for (quantity, value) in [("mass", body.mass), ("moment of inertia", body.inertia)] {
        if !value.is_finite() || value < 0.0 {
            return Err(DynamicsError::BadMass { body: body.name.clone(), quantity, value });
        }
    }
    // The sum in the order `total_mass` takes it.
    if !(total + body.mass).is_finite() {
        return Err(DynamicsError::Overflow { what: "total mass", x: Vec::new(), names: Vec::new() });
    }
    check_point("body", &body.name, body.com, sizes)?;
    check_rotation("body", &body.name, body.rotation, sizes)
}

/// A point's indices checked against the sizes `[n, ni, no]`, its constants finite.
// A `&Cow` (not `&str`): the error clones it, which keeps a borrowed name borrowed.
#[allow(clippy::ptr_arg)]
pub(crate) fn check_point(
    owner: &'static str,
    name: &Cow<'static, str>,
    p: Point,
    [n, _, no]: [usize; 3],
) -> Result<(), DynamicsError> {
    for c in p {
        let (what, index, len) = match c {
            Coord::Output(c) => ("output column", c, no),
            Coord::Unknown(u) => ("unknown", u, n),
            Coord::Fixed(v) if v.is_finite() => continue,
            Coord::Fixed(v) => {
                return Err(DynamicsError::BadValue { what: "fixed coordinate", value: v, why: "must be finite" });
            }
        };
        if index >= len {
            return Err(DynamicsError::IndexOutOfRange { owner, name: name.clone(), what, index, len });
        }
    }
    Ok(())
}

/// An angle's index checked against the sizes `[n, ni, no]`.
#[allow(clippy::ptr_arg)]
pub(crate) fn check_rotation(
    owner: &'static str,
    name: &Cow<'static, str>,
    r: Rotation,
    [n, ni, _]: [usize; 3],
) -> Result<(), DynamicsError> {
    let (what, index, len) = match r {
        Rotation::Unknown(u) => ("unknown", u, n),
        Rotation::Input(i) => ("input", i, ni),
        Rotation::None => return Ok(()),
    };
    if index >= len {
        Err(DynamicsError::IndexOutOfRange { owner, name: name.clone(), what, index, len })
    } else {
        Ok(())
    }
}
