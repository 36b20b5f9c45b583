//! Where things happen: the blocks of a decomposition, locations of errors, and the singular
//! positions (events) met along a path. This vocabulary depends on nothing else in the crate,
//! so errors, sweeps and continuation can all name it (and the leaf that writes a number,
//! which imports nothing).

use crate::number::Number;
use std::borrow::Cow;
use std::fmt;

/// Names as a block description holds them: the constants of a compiled mechanism (borrowed,
/// nothing allocated), or the names of a mechanism read at run time (owned).
pub type BlockNames = Cow<'static, [Cow<'static, str>]>;

/// Description of one block of a mechanism's block-triangular decomposition. A compiled
/// mechanism's are constants (`Name::BLOCKS`, borrowed names); a mechanism read at run time
/// holds its own names.
#[derive(Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct BlockInfo {
    /// Unknowns solved in this block (declaration order).
    pub unknowns: BlockNames,
    /// Scalar equations of this block (`loop.x`, `loop.y` or an `eq` name).
    pub equations: BlockNames,
    /// The block's unknowns appear linearly: it is solved in closed form, without iteration.
    pub linear: bool,
}

impl BlockInfo {
    /// A block of a compiled mechanism: its names are constants (what `mechanism!` emits).
    pub const fn borrowed(
        unknowns: &'static [Cow<'static, str>],
        equations: &'static [Cow<'static, str>],
        linear: bool,
    ) -> Self {
        BlockInfo { unknowns: Cow::Borrowed(unknowns), equations: Cow::Borrowed(equations), linear }
    }

    /// A block of a mechanism read at run time: its unknowns and equations by name.
    pub fn owned(unknowns: Vec<String>, equations: Vec<String>, linear: bool) -> Self {
        let names = |v: Vec<String>| Cow::Owned(v.into_iter().map(Cow::Owned).collect());
        BlockInfo { unknowns: names(unknowns), equations: names(equations), linear }
    }
}

/// Where an error happened.
#[derive(Clone, Debug, PartialEq)]
pub struct Location {
    /// Name of the mechanism type: borrowed for a compiled mechanism, owned for one read at run
    /// time.
    pub mechanism: Cow<'static, str>,
    /// Values of the inputs (generalized coordinates) when it happened, by name.
    pub inputs: Vec<(Cow<'static, str>, f64)>,
    /// The block being solved, with its index in solve order, if the error concerns one.
    pub block: Option<(usize, BlockInfo)>,
}

impl Location {
    /// A boxed location of mechanism `mechanism` at the inputs `names = x` (for errors raised
    /// by generic code: sweeps, continuation).
    pub(crate) fn boxed(
        mechanism: &'static str,
        names: &[&'static str],
        x: &[f64],
        block: Option<(usize, BlockInfo)>,
    ) -> Box<Location> {
        Box::new(Location {
            mechanism: Cow::Borrowed(mechanism),
            inputs: names.iter().map(|&n| Cow::Borrowed(n)).zip(x.iter().copied()).collect(),
            block,
        })
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "in `{}`", self.mechanism)?;
        if !self.inputs.is_empty() {
            write!(f, " at ")?;
            for (k, (name, value)) in self.inputs.iter().enumerate() {
                if k > 0 {
                    write!(f, ", ")?;
                }
                write!(f, "{name} = {}", Number(*value))?;
            }
        }
        if let Some((index, info)) = &self.block {
            write!(
                f,
                " (block {index}: unknowns {}; equations {})",
                info.unknowns.join(", "),
                info.equations.join(", ")
            )?;
        }
        Ok(())
    }
}

/// Kinds of singular positions met along a sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum EventKind {
    /// The input cannot advance on this branch: a limit (dead-centre) position of the input, a
    /// fold of the solution curve where the input reverses.
    LimitPosition,
    /// A block's Jacobian is singular with solutions on both sides and its determinant changes
    /// sign: a change point (bifurcation) where the assembly mode can change.
    ///
    /// A sweep cannot tell a change point from a regular position where two assembly modes
    /// pass nearer each other than the residual tolerance separates them, its pivot ratio below
    /// [`singular_pivot`](crate::SweepConfig::singular_pivot): such a position is reported as a
    /// crossing too, and with [`AtSingular::Continue`](crate::AtSingular::Continue) the sweep
    /// goes on in the other assembly mode. A four-bar whose coupler and follower come within
    /// about `0.9 * singular_pivot` rad of lying in line is one: at the default `1e-6`, a
    /// crank-rocker within a few `1e-14` of a change point (its
    /// [`Grashof::margin`](crate::metrics::Grashof::margin), a threshold that grows as the
    /// square of `singular_pivot`) meets a `SingularCrossing` at its dead centre instead of
    /// turning fully, and a triple rocker as near meets one instead of its `LimitPosition`. (A
    /// position as near singular with no other mode beside it, a slide brushing its pivot,
    /// stops the sweep with [`Error::NearSingular`](crate::Error::NearSingular) instead.)
    SingularCrossing,
    /// A corner of the solution curve where the Jacobian is regular: the positions are
    /// continuous but the velocity analogs jump (the acceleration is unbounded there), as a
    /// function with a corner in the equations makes (`abs`, `min`, `max`, `clamp`: e.g. a
    /// uniform-velocity cam law). A sweep records it and goes on; `x` and `q` are the first
    /// state past it, within the sweep's smallest step of the corner. A corner at the start or
    /// the end of a sweep's range (within that step) or of a trace's is not recorded, whichever
    /// way the range goes: the range holds one of its sides only. `sweep_at` records one at an
    /// input between two others, at that input.
    Kink,
}

impl fmt::Display for EventKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            EventKind::LimitPosition => "limit position",
            EventKind::SingularCrossing => "singular crossing",
            EventKind::Kink => "kink",
        })
    }
}

/// A singular position, or a kink, located along a sweep.
///
/// With the feature `serde` it serializes completely; the block's static description is not
/// read back (`block` deserializes as `None`), since it names the mechanism's own equations.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Event {
    /// What was met.
    pub kind: EventKind,
    /// Input values at the event, located as closely as the positions around it allow: a limit
    /// position, and a singular crossing with well-conditioned positions near it on both sides
    /// (a pivot ratio of at least 1e-3 within 0.15 of the input's unit, through which the
    /// determinant is interpolated), within 1e-9 of the input's unit (the tests' bound; most
    /// lie far closer). Where two branches meet at so small an angle that the positions stay
    /// nearly singular farther out (a four-bar some thousandths of its size from a kite, at
    /// its change point), a crossing is located to a few millionths, about the square root of
    /// the residual tolerance.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub x: Vec<f64>,
    /// Fraction of the sweep path at the event (`0` at `from`, `1` at `to`).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub tau: f64,
    /// Positions of the unknowns at the event.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub q: Vec<f64>,
    /// The block that became singular, if identified, with its index in solve order.
    #[cfg_attr(feature = "serde", serde(skip_deserializing))]
    pub block: Option<(usize, BlockInfo)>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An input's value is written as a table's CSV writes it: positional when ordinary, in
    /// exponent notation when far from one (not 301 digits, nor 300 zeros).
    #[test]
    fn a_location_writes_its_inputs_as_numbers_read() {
        let at = |x: &[f64]| Location::boxed("FourBar", &["phi", "s"][..x.len()], x, None).to_string();
        assert_eq!(at(&[0.5]), "in `FourBar` at phi = 0.5");
        assert_eq!(at(&[1e300, -0.0]), "in `FourBar` at phi = 1e300, s = -0");
        assert_eq!(at(&[1e-300, 2.0816681711721685e-17]), "in `FourBar` at phi = 1e-300, s = 2.0816681711721685e-17");
        assert_eq!(at(&[150.0, 0.1 + 0.2]), "in `FourBar` at phi = 150, s = 0.30000000000000004");
    }
}
