//! The configuration of the Newton solver, apart from the problem (the block's evaluation) and
//! from the iteration itself (see [`newton`](super::newton)).

use crate::error::Error;

/// Tolerances and limits of the Newton solver.
///
/// ```
/// use kinloop_runtime::NewtonConfig;
/// let cfg = NewtonConfig::default().with_residual_tol(1e-10).with_max_iterations(20);
/// assert_eq!(cfg.max_iterations, 20);
/// assert!(cfg.validate().is_ok());
/// assert!(NewtonConfig::default().with_residual_tol(f64::INFINITY).validate().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub struct NewtonConfig {
    /// Converged when every residual is at most this fraction of its row magnitude,
    /// `max_i |f_i| / scale_i <= residual_tol` (default `1e-12`; valid range `[0, 1e-3]`; `0`
    /// iterates down to the rounding floor).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub residual_tol: f64,
    /// Also stops when a full Newton step is at most this fraction of each unknown's magnitude
    /// (default `1e-13`; valid range `[0, 1e-3]`), or when the residual stops decreasing; the
    /// step is then applied and the scaled residual must still be within
    /// `1000 * max(residual_tol, 16 eps)` (the rounding floor of rows whose terms are much
    /// larger than their derivatives, e.g. near a limit position); where the Jacobian's pivot
    /// ratio is at most [`NewtonConfig::singular_tol`], within `residual_tol` itself, or the
    /// stop is a stall at the block's singular position.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub step_tol: f64,
    /// Iteration cap per block (default `50`; at most `10_000`).
    pub max_iterations: u32,
    /// A block whose equilibrated pivot ratio falls below this is singular (default `1e-10`;
    /// valid range `[0, 1)`): Newton's factorisations have their rows divided by the rows'
    /// magnitudes and their columns multiplied by the unknowns' units, the analogs' their
    /// columns divided by their largest entries, so that the test is the same at every size of
    /// the mechanism. (A Newton pivot may exceed 1 where a length's unit exceeds its entries.)
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub singular_tol: f64,
    /// Smallest damping factor of the backtracking line search (default `2^-12`; valid range
    /// `[1e-12, 1)`).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub min_damping: f64,
    /// Whether a block whose iteration stalls away from every root is solved again from
    /// restarts before it is reported as [`Error::NoAssembly`] (default `true`). A far guess can
    /// lead the iteration into a local minimum of the residual where no step decreases it,
    /// though the loops close elsewhere. The restarts are the guess with one angle at a time
    /// turned by a quarter turn either way and by a half turn (the angles whose equations
    /// repeat every turn, in blocks of up to eight of them); of the roots they reach, the one
    /// nearest the guess is returned, on the guess's turns. Continuations (a sweep's steps,
    /// whose guesses are predictions) never restart: a root reached from a turned guess would
    /// be another branch.
    #[cfg_attr(feature = "serde", serde(default = "restarts_default"))]
    pub restarts: bool,
}

/// The default of [`NewtonConfig::restarts`], for configurations serialised without it.
#[cfg(feature = "serde")]
fn restarts_default() -> bool {
    true
}

impl Default for NewtonConfig {
    fn default() -> Self {
        NewtonConfig {
            residual_tol: 1e-12,
            step_tol: 1e-13,
            max_iterations: 50,
            singular_tol: 1e-10,
            min_damping: 1.0 / 4096.0,
            restarts: true,
        }
    }
}

impl NewtonConfig {
    /// Sets [`NewtonConfig::residual_tol`].
    pub fn with_residual_tol(mut self, tol: f64) -> Self {
        self.residual_tol = tol;
        self
    }
    /// Sets [`NewtonConfig::step_tol`].
    pub fn with_step_tol(mut self, tol: f64) -> Self {
        self.step_tol = tol;
        self
    }
    /// Sets [`NewtonConfig::max_iterations`].
    pub fn with_max_iterations(mut self, n: u32) -> Self {
        self.max_iterations = n;
        self
    }
    /// Sets [`NewtonConfig::singular_tol`].
    pub fn with_singular_tol(mut self, tol: f64) -> Self {
        self.singular_tol = tol;
        self
    }
    /// Sets [`NewtonConfig::min_damping`].
    pub fn with_min_damping(mut self, t: f64) -> Self {
        self.min_damping = t;
        self
    }
    /// Sets [`NewtonConfig::restarts`].
    pub fn with_restarts(mut self, on: bool) -> Self {
        self.restarts = on;
        self
    }

    /// The magnitude (in radians) beyond which an angle cannot be solved to this
    /// configuration's tolerance: the spacing of doubles there (`|angle| * 2.2e-16`) exceeds
    /// the precision the residual floor accepts (1000 times [`NewtonConfig::residual_tol`], at
    /// least 16 eps). About 4.5e6 rad (700,000 turns) by default. A guess beyond it is
    /// [`Error::TooManyTurns`](crate::Error::TooManyTurns); a program that converts an angle
    /// to radians (from degrees) loses as much in the conversion there.
    ///
    /// ```
    /// use kinloop_runtime::NewtonConfig;
    /// let largest = NewtonConfig::default().largest_precise_angle();
    /// assert!(largest > 4e6 && largest < 5e6);
    /// ```
    #[inline]
    pub fn largest_precise_angle(&self) -> f64 {
        1000.0 * self.residual_tol.max(16.0 * f64::EPSILON) / f64::EPSILON
    }

    /// The first field outside its valid range (NaN is outside every range).
    #[inline]
    pub fn invalid_field(&self) -> Option<&'static str> {
        // Every step of a closed-form mechanism checks its configuration: the common valid case
        // is one branch-free conjunction (NaN fails every comparison); the field is named on the
        // cold path.
        let valid = (self.residual_tol >= 0.0)
            & (self.residual_tol <= 1e-3)
            & (self.step_tol >= 0.0)
            & (self.step_tol <= 1e-3)
            & (self.max_iterations <= 10_000)
            & (self.singular_tol >= 0.0)
            & (self.singular_tol < 1.0)
            & (self.min_damping >= 1e-12)
            & (self.min_damping < 1.0);
        if valid { None } else { self.first_invalid_field() }
    }

    #[cold]
    #[inline(never)]
    fn first_invalid_field(&self) -> Option<&'static str> {
        let within = |v: f64, lo: f64, hi: f64, lo_open: bool| (if lo_open { v > lo } else { v >= lo }) && v <= hi;
        if !within(self.residual_tol, 0.0, 1e-3, false) {
            Some("residual_tol")
        } else if !within(self.step_tol, 0.0, 1e-3, false) {
            Some("step_tol")
        } else if self.max_iterations > 10_000 {
            Some("max_iterations")
        } else if !(within(self.singular_tol, 0.0, 1.0, false) && self.singular_tol < 1.0) {
            Some("singular_tol")
        } else if !(within(self.min_damping, 1e-12, 1.0, false) && self.min_damping < 1.0) {
            Some("min_damping")
        } else {
            None
        }
    }

    /// The valid range of a field [`NewtonConfig::invalid_field`] names, in the words its
    /// error states (those of the field's documentation).
    pub(crate) fn valid_range(field: &str) -> &'static str {
        match field {
            "residual_tol" | "step_tol" => "[0, 1e-3]",
            "max_iterations" => "at most 10000",
            "singular_tol" => "[0, 1)",
            "min_damping" => "[1e-12, 1)",
            _ => "as its documentation states",
        }
    }

    /// Checks every field: `Error::InvalidArgument` names the first one out of range and states
    /// its valid range.
    ///
    /// ```
    /// use kinloop_runtime::NewtonConfig;
    /// let e = NewtonConfig::default().with_singular_tol(1.5).validate().unwrap_err();
    /// assert!(e.to_string().contains("NewtonConfig::singular_tol is out of its valid range, [0, 1)"));
    /// ```
    pub fn validate(&self) -> Result<(), Error> {
        let field = self.invalid_field();
        crate::error::check_fields("NewtonConfig", field.map(|f| (f, Self::valid_range(f))), self)
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_blocks::{circle, solve};
    use super::*;
    use crate::solvers::newton::BlockFailure;

    #[test]
    fn out_of_range_configurations_are_named() {
        for (cfg, field) in [
            (NewtonConfig::default().with_residual_tol(f64::INFINITY), "residual_tol"),
            (NewtonConfig::default().with_residual_tol(f64::NAN), "residual_tol"),
            (NewtonConfig::default().with_step_tol(-1.0), "step_tol"),
            (NewtonConfig::default().with_singular_tol(f64::NAN), "singular_tol"),
            (NewtonConfig::default().with_min_damping(0.0), "min_damping"),
        ] {
            assert_eq!(cfg.invalid_field(), Some(field));
            let e = solve([1.0, 1.0], &cfg, circle).unwrap_err();
            assert_eq!(e, BlockFailure::InvalidConfig { field });
        }
    }

    #[test]
    fn every_field_s_error_states_its_documented_range() {
        for (cfg, range) in [
            (NewtonConfig::default().with_residual_tol(2e-3), "[0, 1e-3]"),
            (NewtonConfig::default().with_step_tol(f64::NAN), "[0, 1e-3]"),
            (NewtonConfig::default().with_max_iterations(10_001), "at most 10000"),
            (NewtonConfig::default().with_singular_tol(1.0), "[0, 1)"),
            (NewtonConfig::default().with_min_damping(1e-13), "[1e-12, 1)"),
        ] {
            let field = cfg.invalid_field().unwrap();
            let message = cfg.validate().unwrap_err().to_string();
            assert!(
                message.contains(&format!("NewtonConfig::{field} is out of its valid range, {range}: ")),
                "{message}"
            );
        }
    }
}
