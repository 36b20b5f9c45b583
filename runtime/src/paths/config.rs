//! The configuration of a sweep ([`SweepConfig`], with what it does at a singular crossing,
//! [`AtSingular`]), apart from the sweep it configures: a mechanism carries one as its solver
//! configuration (`Mechanism::solver_config`), and every path of the runtime takes one, so it
//! sits below them all and below the mechanism's traits.

use crate::error::Error;
use crate::solvers::newton::NewtonConfig;

/// What a sweep does at a singular crossing (a change point where a block's determinant changes
/// sign and the mechanism can continue on either branch).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum AtSingular {
    /// Record the event and stop with [`Error::SweepStopped`] (default).
    Stop,
    /// Record the event and continue on the smooth continuation of the path. A sample at the
    /// crossing itself, or so near it (on either side) that its state's pivot ratio would be
    /// below [`SweepConfig::singular_pivot`], where no solve pins the branch, is the first
    /// well-conditioned state past the crossing (pivot ratio at least 100 times
    /// `singular_pivot`), at that state's own input (`Kin::x`): a parallelogram four-bar's crank
    /// sampled every 10 degrees gives at 180 degrees the state at about 180.07. So is a later
    /// sample that lies before that state (where samples are closer together than its way past
    /// the crossing, about 2e-3 rad for a Grashof-equal four-bar); every other sample is the
    /// state at its own input.
    Continue,
}

/// Configuration of a sweep, built from the default with the `with_*` methods.
///
/// ```
/// use kinloop_runtime::{AtSingular, NewtonConfig, SweepConfig};
/// let cfg = SweepConfig::default()
///     .with_newton(NewtonConfig::default().with_residual_tol(1e-14))
///     .with_max_step(0.5)
///     .with_at_singular(AtSingular::Continue);
/// assert_eq!(cfg.max_step, 0.5);
/// assert_eq!(cfg.newton.residual_tol, 1e-14);
/// assert!(cfg.validate().is_ok());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct SweepConfig {
    /// The Newton solver used at every step. Its [`NewtonConfig::restarts`] apply to the first
    /// sample only, solved from the caller's guess: a step's guess is a prediction, and a root
    /// reached from a turned guess would be another branch.
    pub newton: NewtonConfig,
    /// Largest internal step as a fraction of the sample spacing (default `1`; at least `1e-6`,
    /// so that a sample takes at most a million steps). Whatever it is, a step is also at most
    /// [`Sweep`](super::sweep::Sweep)'s natural bound (a quarter radian of an angle input), so the number of samples
    /// never sets how far a step goes.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub max_step: f64,
    /// How many times a step may be halved before the sweep diagnoses a singular position
    /// (default `40`, i.e. steps down to about `1e-12` of the sample spacing).
    pub max_halvings: u32,
    /// A corrected position is accepted only within `corrector_rel` times the predicted change
    /// plus `corrector_abs` of its prediction (defaults `0.25` and `1e-6`), and its slopes
    /// likewise: every unknown in its own unit (radians for an angle, its loop's size for a
    /// length), so that the test is the same in any unit of length.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub corrector_rel: f64,
    /// See [`SweepConfig::corrector_rel`].
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub corrector_abs: f64,
    /// Behaviour at a singular crossing.
    pub at_singular: AtSingular,
    /// A step is not accepted at a position whose smallest pivot ratio
    /// ([`Health::min_pivot`](crate::Health::min_pivot)) is below this (default `1e-6`): so close
    /// to a singular position the residual tolerance no longer pins the branch. The sweep then locates the singular position by arclength
    /// continuation; where it finds none (the path only passes close to one, e.g. a slide within
    /// a millionth of its loop's size from its pivot) it stops with [`Error::NearSingular`], and a
    /// lower value lets it pass. A sweep whose first sample is below it (a limit position, the
    /// end of a reachable range) stops with [`Error::SingularStart`].
    ///
    /// A lower value also weakens what this test protects: a sweep run with `1e-9` (or `0`)
    /// through the change point of a parallelogram or a kite four-bar has been seen to complete
    /// without a crossing event, its later samples on the other branch. Lower it only past a
    /// near-singular position the default refuses, over a range that holds no change point.
    /// Below the default the residual tolerance cannot tell the two apart: a check that
    /// followed the curve from the last position the default pins found the parallelogram's
    /// crossing, and found crossings just as well beside a slide passing a billionth of its
    /// size from its pivot, which has none. A corner of the curve (a kink event) is told from a
    /// jump to another solution only where the pivot ratio is at least the default's, whatever
    /// this value: below it, two branches lie closer than a corner's two sides may.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub singular_pivot: f64,
}

/// The sweep defaults with this Newton configuration.
impl From<NewtonConfig> for SweepConfig {
    fn from(newton: NewtonConfig) -> Self {
        SweepConfig::default().with_newton(newton)
    }
}

impl Default for SweepConfig {
    fn default() -> Self {
        SweepConfig {
            newton: NewtonConfig::default(),
            max_step: 1.0,
            max_halvings: 40,
            corrector_rel: 0.25,
            corrector_abs: 1e-6,
            at_singular: AtSingular::Stop,
            singular_pivot: 1e-6,
        }
    }
}

impl SweepConfig {
    /// Sets [`SweepConfig::newton`].
    pub fn with_newton(mut self, newton: NewtonConfig) -> Self {
        self.newton = newton;
        self
    }
    /// Sets [`SweepConfig::max_step`].
    pub fn with_max_step(mut self, fraction: f64) -> Self {
        self.max_step = fraction;
        self
    }
    /// Sets [`SweepConfig::max_halvings`].
    pub fn with_max_halvings(mut self, n: u32) -> Self {
        self.max_halvings = n;
        self
    }
    /// Sets [`SweepConfig::corrector_rel`] and [`SweepConfig::corrector_abs`].
    pub fn with_corrector(mut self, rel: f64, abs: f64) -> Self {
        self.corrector_rel = rel;
        self.corrector_abs = abs;
        self
    }
    /// Sets [`SweepConfig::at_singular`].
    pub fn with_at_singular(mut self, at_singular: AtSingular) -> Self {
        self.at_singular = at_singular;
        self
    }
    /// Sets [`SweepConfig::singular_pivot`].
    pub fn with_singular_pivot(mut self, ratio: f64) -> Self {
        self.singular_pivot = ratio;
        self
    }

    /// The first field outside its valid range (NaN is outside every range), including the
    /// fields of [`SweepConfig::newton`].
    pub fn invalid_field(&self) -> Option<&'static str> {
        let finite_positive = |v: f64| v > 0.0 && v < f64::INFINITY;
        if let Some(field) = self.newton.invalid_field() {
            Some(field)
        } else if !(self.max_step >= MIN_MAX_STEP && self.max_step <= 1.0) {
            Some("max_step")
        } else if !(1..=60).contains(&self.max_halvings) {
            Some("max_halvings")
        } else if !finite_positive(self.corrector_rel) {
            Some("corrector_rel")
        } else if !(self.corrector_abs >= 0.0 && self.corrector_abs < f64::INFINITY) {
            Some("corrector_abs")
        } else if !(self.singular_pivot >= 0.0 && self.singular_pivot < 1.0) {
            Some("singular_pivot")
        } else {
            None
        }
    }

    /// Checks every field: `Error::InvalidArgument` names the first one out of range
    /// (`max_step` in `[1e-6, 1]`, `max_halvings` in `1..=60`, `corrector_rel` positive and finite,
    /// `corrector_abs` non-negative and finite, `singular_pivot` in `[0, 1)`, and the Newton
    /// configuration's ranges).
    ///
    /// ```
    /// use kinloop_runtime::SweepConfig;
    /// assert!(SweepConfig::default().validate().is_ok());
    /// let bad = SweepConfig::default().with_max_step(0.0);
    /// assert!(bad.validate().unwrap_err().to_string().contains("max_step"));
    /// ```
    pub fn validate(&self) -> Result<(), Error> {
        let field = match self.newton.invalid_field() {
            Some(field) => Some((format!("newton.{field}"), NewtonConfig::valid_range(field))),
            None => self.invalid_field().map(|field| (field.to_string(), Self::valid_range(field))),
        };
        crate::error::check_fields("SweepConfig", field, self)
    }

    /// The valid range of a field of its own [`SweepConfig::invalid_field`] names, in the words
    /// its error states (those of [`SweepConfig::validate`]).
    fn valid_range(field: &str) -> &'static str {
        match field {
            "max_step" => "[1e-6, 1]",
            "max_halvings" => "1..=60",
            "corrector_rel" => "positive and finite",
            "corrector_abs" => "not negative and finite",
            "singular_pivot" => "[0, 1)",
            _ => "as its documentation states",
        }
    }
}

/// Smallest valid [`SweepConfig::max_step`]: below it a sample would take more than a million
/// steps, beyond any use (the sample spacing is the user's to choose instead).
const MIN_MAX_STEP: f64 = 1e-6;

#[cfg(test)]
mod tests {
    use super::*;

    /// The range an error states is the one `invalid_field` tests: `max_step`'s written out
    /// is its bound's constant.
    #[test]
    fn the_ranges_stated_are_the_ranges_tested() {
        assert_eq!(SweepConfig::valid_range("max_step"), format!("[{MIN_MAX_STEP:e}, 1]"));
        let at = |max_step: f64| SweepConfig::default().with_max_step(max_step).invalid_field();
        assert_eq!(at(MIN_MAX_STEP), None);
        assert_eq!(at(1.0), None);
        assert_eq!(at(MIN_MAX_STEP.next_down()), Some("max_step"));
        assert_eq!(at(1f64.next_up()), Some("max_step"));
    }
}
