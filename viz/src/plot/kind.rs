//! What a series holds: the quantity kind of its values, which fixes the axis unit and how the
//! values are shown (angles in degrees).

use std::fmt;

/// The quantity kind of a series' values (and of the axis that shows them). An axis holds one
/// kind: series of different kinds go on different axes (panels).
///
/// Values are given in the library's units: angles in radians (shown in degrees), lengths in
/// the mechanism's unit, named here so the axis can say it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Kind {
    /// An angle, given in radians, shown in degrees (ticks at multiples of 90 degrees over a
    /// turn).
    Angle,
    /// A length in the named unit (`"mm"`, `"m"`).
    Length(String),
    /// Velocity analog of an angle with respect to an angle input, `d psi / d phi` [rad/rad].
    AngleAnalog,
    /// Acceleration analog of an angle, `d2 psi / d phi2` [rad/rad²].
    AngleAnalog2,
    /// Velocity analog of a length with respect to an angle input, `dx / d phi` [unit/rad].
    LengthAnalog(String),
    /// Acceleration analog of a length, `d2x / d phi2` [unit/rad²].
    LengthAnalog2(String),
    /// A pure number (a ratio, a count) [-].
    Dimensionless,
    /// Any other quantity, with its name (`"force"`) and unit (`"N"`).
    Other {
        /// The quantity's name.
        quantity: String,
        /// Its unit.
        unit: String,
    },
}

impl Kind {
    /// A length in `unit`.
    pub fn length(unit: &str) -> Kind {
        Kind::Length(unit.to_string())
    }

    /// The unit written on the axis.
    pub fn unit(&self) -> String {
        match self {
            Kind::Angle => "°".into(),
            Kind::Length(u) => u.clone(),
            Kind::AngleAnalog => "rad/rad".into(),
            Kind::AngleAnalog2 => "rad/rad²".into(),
            Kind::LengthAnalog(u) => format!("{u}/rad"),
            Kind::LengthAnalog2(u) => format!("{u}/rad²"),
            Kind::Dimensionless => "-".into(),
            Kind::Other { unit, .. } => unit.clone(),
        }
    }

    /// A generic name of the quantity, for an axis the caller did not name.
    pub fn quantity(&self) -> String {
        match self {
            Kind::Angle => "angle".into(),
            Kind::Length(_) => "length".into(),
            Kind::AngleAnalog => "angle velocity analog".into(),
            Kind::AngleAnalog2 => "angle acceleration analog".into(),
            Kind::LengthAnalog(_) => "length velocity analog".into(),
            Kind::LengthAnalog2(_) => "length acceleration analog".into(),
            Kind::Dimensionless => "ratio".into(),
            Kind::Other { quantity, .. } => quantity.clone(),
        }
    }

    /// Whether values are angles (shown in degrees, ticked in degree steps).
    pub fn is_angle(&self) -> bool {
        matches!(self, Kind::Angle)
    }

    /// A value as shown on the axis (radians to degrees for angles).
    pub fn shown(&self, v: f64) -> f64 {
        if self.is_angle() { v.to_degrees() } else { v }
    }

    /// Shown units per value unit (degrees per radian for angles, else 1).
    pub(crate) fn factor(&self) -> f64 {
        self.shown(1.0)
    }
}

impl fmt::Display for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} [{}]", self.quantity(), self.unit())
    }
}

/// An axis: what it shows (a name such as `"crank angle φ"`) and the kind of its values.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// What the axis shows.
    pub name: String,
    /// The kind of its values.
    pub kind: Kind,
}

impl Axis {
    /// An axis called `name` holding values of `kind`.
    pub fn new(name: &str, kind: Kind) -> Axis {
        Axis { name: name.to_string(), kind }
    }

    /// An angle axis (values in radians, shown in degrees).
    pub fn angle(name: &str) -> Axis {
        Axis::new(name, Kind::Angle)
    }

    /// A length axis in `unit`.
    pub fn length(name: &str, unit: &str) -> Axis {
        Axis::new(name, Kind::length(unit))
    }

    /// An axis named after its kind (`"length [mm]"`).
    pub fn of(kind: Kind) -> Axis {
        Axis { name: kind.quantity(), kind }
    }

    /// The axis title with its unit: `"crank angle φ [°]"`.
    pub fn title(&self) -> String {
        format!("{} [{}]", self.name, self.kind.unit())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn titles_carry_units() {
        assert_eq!(Axis::angle("crank angle φ").title(), "crank angle φ [°]");
        assert_eq!(Axis::new("x'", Kind::LengthAnalog("mm".into())).title(), "x' [mm/rad]");
        assert_eq!(Axis::of(Kind::Dimensionless).title(), "ratio [-]");
        assert!((Kind::Angle.shown(std::f64::consts::PI) - 180.0).abs() < 1e-12);
    }
}
