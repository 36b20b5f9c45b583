//! What kind of computed value an [`Error::Domain`](crate::Error::Domain) or
//! [`Error::Overflow`](crate::Error::Overflow) names: a typed field a program matches on, where
//! it read a label before (a label's spelling is the message's, not an interface).

use std::fmt;

/// Which computed value left its domain or the range of `f64`: an equation's terms, a state's
/// position, analogs or outputs, its true motion, or a parameter sensitivity.
///
/// Its `Display` is the phrase the error's message uses ("velocity analog", "output
/// acceleration", ...).
///
/// ```
/// use kinloop_runtime::Computed;
/// assert!(Computed::OutputAccelerationAnalog.is_acceleration());
/// assert!(Computed::OutputAccelerationAnalog.is_output());
/// assert!(!Computed::VelocityAnalog.is_output());
/// assert_eq!(Computed::VelocityAnalog.to_string(), "velocity analog");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Computed {
    /// An equation (its residual or the magnitude of its terms).
    Equation,
    /// An unknown's position.
    Position,
    /// An unknown's velocity analog `dq/dx`.
    VelocityAnalog,
    /// An unknown's acceleration analog `d²q/dx²`.
    AccelerationAnalog,
    /// A named output's value.
    Output,
    /// A named output's velocity analog.
    OutputVelocityAnalog,
    /// A named output's acceleration analog.
    OutputAccelerationAnalog,
    /// An unknown's true velocity (`motion`: the analogs times the input speeds).
    Velocity,
    /// An unknown's true acceleration.
    Acceleration,
    /// A named output's true velocity.
    OutputVelocity,
    /// A named output's true acceleration.
    OutputAcceleration,
    /// The sensitivity of a position, analog or output to a parameter.
    ParameterSensitivity,
    /// A value of the state that could not be told apart (none found non-finite where the state
    /// as a whole was not).
    Value,
}

impl Computed {
    /// A value of a named output (value, analogs or true motion), not of an unknown.
    pub fn is_output(self) -> bool {
        matches!(
            self,
            Computed::Output
                | Computed::OutputVelocityAnalog
                | Computed::OutputAccelerationAnalog
                | Computed::OutputVelocity
                | Computed::OutputAcceleration
        )
    }

    /// An acceleration: an analog of the second order or a true acceleration, of an unknown or
    /// an output. These are the values that leave `f64`'s range first as a mechanism shrinks
    /// (about `1 / size²` by a length input) or its speeds grow.
    pub fn is_acceleration(self) -> bool {
        matches!(
            self,
            Computed::AccelerationAnalog
                | Computed::OutputAccelerationAnalog
                | Computed::Acceleration
                | Computed::OutputAcceleration
        )
    }
}

impl fmt::Display for Computed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Computed::Equation => "equation",
            Computed::Position => "position",
            Computed::VelocityAnalog => "velocity analog",
            Computed::AccelerationAnalog => "acceleration analog",
            Computed::Output => "output",
            Computed::OutputVelocityAnalog => "output velocity analog",
            Computed::OutputAccelerationAnalog => "output acceleration analog",
            Computed::Velocity => "velocity",
            Computed::Acceleration => "acceleration",
            Computed::OutputVelocity => "output velocity",
            Computed::OutputAcceleration => "output acceleration",
            Computed::ParameterSensitivity => "parameter sensitivity of",
            Computed::Value => "value",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::Computed;

    /// Every kind's phrase, and its two classes, as the messages and the analyses read them.
    #[test]
    fn phrases_and_classes() {
        let all = [
            (Computed::Equation, "equation", false, false),
            (Computed::Position, "position", false, false),
            (Computed::VelocityAnalog, "velocity analog", false, false),
            (Computed::AccelerationAnalog, "acceleration analog", false, true),
            (Computed::Output, "output", true, false),
            (Computed::OutputVelocityAnalog, "output velocity analog", true, false),
            (Computed::OutputAccelerationAnalog, "output acceleration analog", true, true),
            (Computed::Velocity, "velocity", false, false),
            (Computed::Acceleration, "acceleration", false, true),
            (Computed::OutputVelocity, "output velocity", true, false),
            (Computed::OutputAcceleration, "output acceleration", true, true),
            (Computed::ParameterSensitivity, "parameter sensitivity of", false, false),
            (Computed::Value, "value", false, false),
        ];
        for (kind, phrase, output, acceleration) in all {
            assert_eq!(kind.to_string(), phrase);
            assert_eq!(kind.is_output(), output, "{kind:?}");
            assert_eq!(kind.is_acceleration(), acceleration, "{kind:?}");
        }
    }
}
