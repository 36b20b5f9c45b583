//! Optional requirements every candidate is checked against after its local solve, beyond
//! meeting the targets on one assembly mode in order (which is always checked): the targets met
//! within a bound, the input turns fully, a smallest transmission angle, a largest ratio of
//! link lengths.

/// The transmission angle to report (and bound from below): the acute angle between the lines
/// of a coupler and the follower it drives, each given by an angle column.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TransmissionBound {
    /// The coupler's angle column (an unknown or an output).
    pub coupler: String,
    /// The follower's angle column.
    pub follower: String,
    /// The smallest acceptable transmission angle (radians; `0` only reports it).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub min: f64,
}

/// The largest acceptable ratio of the longest to the shortest of some parameters (link
/// lengths).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LinkRatioBound {
    /// The parameters compared (at least two).
    pub links: Vec<String>,
    /// The largest acceptable ratio of the longest to the shortest (at least 1).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub max: f64,
}

/// The parameters that are the four link lengths of a four-bar (their absolute values), for
/// the Grashof class and the closed-form transmission angle of every candidate
/// ([`Candidate::four_bar`](super::Candidate::four_bar)).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FourBarNames {
    /// The ground link, between the fixed pivots.
    pub ground: String,
    /// The input (driven) link.
    pub input: String,
    /// The coupler.
    pub coupler: String,
    /// The output (follower) link.
    pub output: String,
}

/// The optional requirements (none by default).
///
/// ```
/// use kinloop_runtime::synthesis::Constraints;
/// let c = Constraints::default()
///     .with_full_rotation()
///     .with_transmission("beta", "gamma", 30f64.to_radians())
///     .with_link_ratio(&["a", "b", "c", "d"], 6.0)
///     .with_four_bar("d", "a", "b", "c")
///     .with_max_error(1e-3);
/// assert!(c.full_rotation);
/// assert_eq!(c.max_error, Some(1e-3));
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Constraints {
    /// The (single) input must turn fully on the candidate's assembly mode: a sweep over one
    /// turn from the first target closes on the position it started from (a Grashof crank for
    /// a four-bar, found for any mechanism).
    pub full_rotation: bool,
    /// Transmission angle to report and bound (over the motion checked: from the first to the
    /// last target, or the whole turn with [`Constraints::full_rotation`]; its minimum located
    /// between the verifying sweep's samples, at a root of the relative angle's velocity analog).
    pub transmission: Option<TransmissionBound>,
    /// Bound on a ratio of link lengths.
    pub link_ratio: Option<LinkRatioBound>,
    /// The four links of a four-bar, to report every candidate's Grashof class and smallest
    /// transmission angle (reported, not required).
    pub four_bar: Option<FourBarNames>,
    /// The largest error accepted at any target, in the units of
    /// [`Candidate::errors`](super::Candidate::errors) (a point's distance from its target in
    /// the mechanism's length unit, an angle's difference in radians, each times its weight).
    /// Without it a candidate that misses its targets far, but meets them on one assembly
    /// mode in order, is valid: the least-squares optimum of designs that cannot reach them.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub max_error: Option<f64>,
}

impl Constraints {
    /// Requires [`Constraints::full_rotation`]. An input inferred as a length or a pure number
    /// turns no turn: refused when the constraints are applied (`Problem::with_constraints`).
    pub fn with_full_rotation(mut self) -> Self {
        self.full_rotation = true;
        self
    }

    /// Reports the transmission angle between the angle columns `coupler` and `follower` and
    /// requires it to stay at least `min` radians. A column inferred as a length or a pure
    /// number is refused when the constraints are applied (`Problem::with_constraints`).
    pub fn with_transmission(mut self, coupler: &str, follower: &str, min: f64) -> Self {
        self.transmission =
            Some(TransmissionBound { coupler: coupler.to_string(), follower: follower.to_string(), min });
        self
    }

    /// Requires the longest of the parameters `links` to be at most `max` times the shortest.
    pub fn with_link_ratio(mut self, links: &[&str], max: f64) -> Self {
        self.link_ratio = Some(LinkRatioBound { links: links.iter().map(|s| s.to_string()).collect(), max });
        self
    }

    /// Requires every target to be met within `max` ([`Constraints::max_error`]): a candidate
    /// that misses one by more has [`Defect::Miss`](super::Defect::Miss). Finite and positive,
    /// or refused when the constraints are applied (`Problem::with_constraints`).
    pub fn with_max_error(mut self, max: f64) -> Self {
        self.max_error = Some(max);
        self
    }

    /// Names the parameters that are a four-bar's `ground`, `input`, `coupler` and `output`
    /// links: every candidate then reports its Grashof class and smallest transmission angle
    /// over the input's range ([`FourBarClass`](super::FourBarClass)).
    pub fn with_four_bar(mut self, ground: &str, input: &str, coupler: &str, output: &str) -> Self {
        self.four_bar = Some(FourBarNames {
            ground: ground.to_string(),
            input: input.to_string(),
            coupler: coupler.to_string(),
            output: output.to_string(),
        });
        self
    }
}
