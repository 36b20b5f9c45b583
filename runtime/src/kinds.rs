//! What kind of quantity a column holds, as inferred by `mechanism!` from the declaration:
//! the source of the units in a table's CSV header.

/// The kind of quantity of an input, unknown or output column.
///
/// `mechanism!` infers it from the declared equations: a leaf that is a term (possibly scaled by
/// numbers or sines and cosines) of a trigonometric argument is an angle, of a loop projection a
/// length; points are lengths; a scalar output gets the kind of its expression when its
/// dimension follows from those (`atan2(..)` an angle, a difference of lengths a length, a ratio
/// of lengths dimensionless). Anything else is [`QuantityKind::Other`]: kinloop does not guess
/// (a time input, a dimensionless factor multiplying a length).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum QuantityKind {
    /// An angle, in radians.
    Angle,
    /// A length, in the unit of the parameters' lengths (which kinloop does not know).
    Length,
    /// A pure number (a ratio of lengths, a sine).
    Dimensionless,
    /// Not inferred: no unit is written (an input of this kind is `unit of NAME`: see
    /// [`QuantityKind::input_unit`]).
    Other,
}

/// The unit written for a length when the table was not told the unit of length.
pub const LENGTH_UNIT: &str = "length unit";

impl QuantityKind {
    /// For the expansion of `mechanism!`: kinds from one letter each (`a`ngle, `l`ength,
    /// `d`imensionless, anything else not inferred), to keep the generated code short. An
    /// upper-case letter is the same kind (it marks an unknown a closed-form block gives as an
    /// angle: [`QuantityKind::__upper_case`]).
    #[doc(hidden)]
    pub const fn __from_codes<const K: usize>(codes: &[u8; K]) -> [QuantityKind; K] {
        let mut out = [QuantityKind::Other; K];
        let mut i = 0;
        while i < K {
            out[i] = match codes[i].to_ascii_lowercase() {
                b'a' => QuantityKind::Angle,
                b'l' => QuantityKind::Length,
                b'd' => QuantityKind::Dimensionless,
                _ => QuantityKind::Other,
            };
            i += 1;
        }
        out
    }

    /// For the expansion of `mechanism!`: which of the letters of [`QuantityKind::__from_codes`]
    /// are upper-case (the unknowns of `Mechanism::CLOSED_FORM_ANGLES`).
    #[doc(hidden)]
    pub const fn __upper_case<const K: usize>(codes: &[u8; K]) -> [bool; K] {
        let mut out = [false; K];
        let mut i = 0;
        while i < K {
            out[i] = codes[i].is_ascii_uppercase();
            i += 1;
        }
        out
    }

    /// The unit written into a CSV header: `rad`, [`LENGTH_UNIT`], `1`, or `""` (none).
    pub const fn unit(self) -> &'static str {
        match self {
            QuantityKind::Angle => "rad",
            QuantityKind::Length => LENGTH_UNIT,
            QuantityKind::Dimensionless => "1",
            QuantityKind::Other => "",
        }
    }

    /// The unit written for an input named `name` of this kind: [`QuantityKind::unit`], but
    /// `unit of NAME` for a kind not inferred (a time `t`: `unit of t`). The analogs by such an
    /// input are per unit of it; without a unit of its own they would have none. kinloop does
    /// not guess a time's unit, so it is named as the input's, as a length's is
    /// [`LENGTH_UNIT`].
    ///
    /// ```
    /// use kinloop_runtime::QuantityKind;
    /// assert_eq!(QuantityKind::Other.input_unit("t"), "unit of t");
    /// assert_eq!(QuantityKind::Angle.input_unit("phi"), "rad");
    /// ```
    pub fn input_unit(self, name: &str) -> std::borrow::Cow<'static, str> {
        match self {
            QuantityKind::Other => format!("unit of {name}").into(),
            kind => kind.unit().into(),
        }
    }
}
