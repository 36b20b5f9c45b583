//! Design variables: parameters of the mechanism, named, each with the range the search may
//! explore. The other parameters keep the values of the mechanism the problem is built from.

use super::error::SynthesisError;

/// A bounded design variable: a parameter of the mechanism by name, and its range.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Variable {
    /// The parameter's declared name.
    pub name: String,
    /// Lower bound.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub lo: f64,
    /// Upper bound.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub hi: f64,
}

impl Variable {
    /// The parameter `name`, varied over `[lo, hi]`.
    pub fn new(name: impl Into<String>, lo: f64, hi: f64) -> Self {
        Variable { name: name.into(), lo, hi }
    }
}

/// The design variables in the order the candidates list their values.
///
/// ```
/// use kinloop_runtime::synthesis::Design;
/// let design = Design::new().var("a", 0.2, 2.0).var("b", 0.5, 5.0);
/// assert_eq!(design.variables().len(), 2);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Design {
    variables: Vec<Variable>,
    /// Whether the problem may have more unknowns than the targets give equations.
    #[cfg_attr(feature = "serde", serde(default))]
    underdetermined: bool,
}

impl Design {
    /// No variable yet.
    pub fn new() -> Self {
        Design::default()
    }

    /// Adds the parameter `name`, varied over `[lo, hi]`.
    pub fn var(mut self, name: impl Into<String>, lo: f64, hi: f64) -> Self {
        self.variables.push(Variable::new(name, lo, hi));
        self
    }

    /// The variables, in order.
    pub fn variables(&self) -> &[Variable] {
        &self.variables
    }

    /// Accepts a problem with more unknowns (design variables, free inputs, placement) than the
    /// targets give scalar equations. Such a task is met by a whole family of designs, not by
    /// one: Levenberg–Marquardt (damped, so its steps stay defined) stops at one member of the
    /// family near each start, and the constraints and the verification choose among them. By
    /// default such a problem is refused ([`SynthesisError::TooFewTargets`]), since its
    /// dimensions are not determined by the task: ask for it when the freedom is wanted (e.g.
    /// the literature's six points on a line with the frame free, where the constraints pick a
    /// crank that turns fully).
    pub fn underdetermined(mut self) -> Self {
        self.underdetermined = true;
        self
    }

    /// Whether [`Design::underdetermined`] was asked for.
    pub fn is_underdetermined(&self) -> bool {
        self.underdetermined
    }

    /// Each variable's index into `params` (the mechanism's parameter names) and its bounds;
    /// an unknown or repeated name, or bounds that hold no value, is an error.
    pub(crate) fn resolve(&self, mechanism: &str, params: &[String]) -> Result<Vec<Bound>, SynthesisError> {
        if self.variables.is_empty() {
            return Err(SynthesisError::NoVariables);
        }
        let mut out: Vec<Bound> = Vec::with_capacity(self.variables.len());
        for v in &self.variables {
            let index = param_index(mechanism, params, &v.name)?;
            if out.iter().any(|b| b.index == index) {
                return Err(SynthesisError::DuplicateVariable { name: v.name.clone() });
            }
            check_bounds(&v.name, v.lo, v.hi)?;
            out.push(Bound { index, lo: v.lo, hi: v.hi });
        }
        Ok(out)
    }
}

/// A resolved variable: the index of what it sets and its bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bound {
    pub index: usize,
    pub lo: f64,
    pub hi: f64,
}

/// The index of the parameter `name`, or an error listing the parameters.
pub(crate) fn param_index(mechanism: &str, params: &[String], name: &str) -> Result<usize, SynthesisError> {
    params.iter().position(|p| p == name).ok_or_else(|| SynthesisError::UnknownVariable {
        name: name.to_string(),
        mechanism: mechanism.to_string().into(),
        params: params.join(", "),
    })
}

/// Bounds must be finite and ordered.
pub(crate) fn check_bounds(name: &str, lo: f64, hi: f64) -> Result<(), SynthesisError> {
    // The width too: the starts are `lo + (hi - lo) t`, infinite for bounds of `±1e308`.
    if lo.is_finite() && hi.is_finite() && lo <= hi && (hi - lo).is_finite() {
        Ok(())
    } else {
        Err(SynthesisError::BadBounds { name: name.to_string(), lo, hi })
    }
}
