//! What a series holds: the quantity kind of its values, which fixes the axis unit and how the
//! values are shown (angles in degrees).

use kinloop_runtime::QuantityKind;
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
    /// A pure number (a ratio, a count, a harmonic's order) [-].
    Dimensionless,
    /// A torque (moment) in the named unit (`"N m"`, `"N mm"`).
    Torque(String),
    /// A force in the named unit (`"N"`, `"kN"`).
    Force(String),
    /// A linear speed in the named unit (`"m/s"`, `"mm/s"`).
    Speed(String),
    /// An angular speed, in rad/s (angles are radians throughout; not converted).
    AngularSpeed,
    /// A time in the named unit (`"s"`, `"ms"`).
    Time(String),
    /// An energy (work) in the named unit (`"J"`, `"N mm"`).
    Energy(String),
    /// A moment of inertia in the named unit (`"kg m²"`).
    Inertia(String),
    /// A power in the named unit (`"W"`, `"kW"`).
    Power(String),
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

    /// A torque in `unit` (`"N m"`).
    pub fn torque(unit: &str) -> Kind {
        Kind::Torque(unit.to_string())
    }

    /// A force in `unit` (`"N"`).
    pub fn force(unit: &str) -> Kind {
        Kind::Force(unit.to_string())
    }

    /// A linear speed in `unit` (`"m/s"`).
    pub fn speed(unit: &str) -> Kind {
        Kind::Speed(unit.to_string())
    }

    /// A time in `unit` (`"s"`).
    pub fn time(unit: &str) -> Kind {
        Kind::Time(unit.to_string())
    }

    /// An energy in `unit` (`"J"`).
    pub fn energy(unit: &str) -> Kind {
        Kind::Energy(unit.to_string())
    }

    /// A moment of inertia in `unit` (`"kg m²"`).
    pub fn inertia(unit: &str) -> Kind {
        Kind::Inertia(unit.to_string())
    }

    /// A power in `unit` (`"W"`).
    pub fn power(unit: &str) -> Kind {
        Kind::Power(unit.to_string())
    }

    /// The kind of a mechanism's column as `mechanism!` inferred it ([`QuantityKind`], which
    /// carries no unit of length), with lengths in `length_unit`: one vocabulary, so a chart of a
    /// table's column needs no kind spelled out again. A column whose kind was not inferred
    /// ([`QuantityKind::Other`]) is a quantity named `"value"` of unknown unit (`"?"`: not
    /// claimed dimensionless); give such a column its kind yourself (`Kind::time("s")`).
    ///
    /// ```
    /// use kinloop_runtime::QuantityKind;
    /// use kinloop_viz::plot::Kind;
    /// assert_eq!(Kind::of_column(QuantityKind::Angle, "mm"), Kind::Angle);
    /// assert_eq!(Kind::of_column(QuantityKind::Length, "mm"), Kind::length("mm"));
    /// ```
    pub fn of_column(kind: QuantityKind, length_unit: &str) -> Kind {
        match kind {
            QuantityKind::Angle => Kind::Angle,
            QuantityKind::Length => Kind::length(length_unit),
            QuantityKind::Dimensionless => Kind::Dimensionless,
            _ => Kind::Other { quantity: "value".into(), unit: "?".into() },
        }
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
            Kind::Torque(u)
            | Kind::Force(u)
            | Kind::Speed(u)
            | Kind::Time(u)
            | Kind::Energy(u)
            | Kind::Inertia(u)
            | Kind::Power(u) => u.clone(),
            Kind::AngularSpeed => "rad/s".into(),
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
            Kind::Torque(_) => "torque".into(),
            Kind::Force(_) => "force".into(),
            Kind::Speed(_) => "speed".into(),
            Kind::AngularSpeed => "angular speed".into(),
            Kind::Time(_) => "time".into(),
            Kind::Energy(_) => "energy".into(),
            Kind::Inertia(_) => "moment of inertia".into(),
            Kind::Power(_) => "power".into(),
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
        assert_eq!(Axis::of(Kind::torque("N m")).title(), "torque [N m]");
        assert_eq!(Axis::of(Kind::AngularSpeed).title(), "angular speed [rad/s]");
        assert_eq!(Axis::of(Kind::inertia("kg m²")).title(), "moment of inertia [kg m²]");
        assert_eq!(Kind::of_column(QuantityKind::Other, "mm").unit(), "?");
    }
}
