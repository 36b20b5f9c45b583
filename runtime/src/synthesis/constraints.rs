//! Optional requirements every candidate is checked against after its local solve, beyond
//! meeting the targets on one assembly mode in order (which is always checked): the input turns
//! fully, a smallest transmission angle, a largest ratio of link lengths.

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
    pub max: f64,
}

/// The optional requirements (none by default).
///
/// ```
/// use kinloop_runtime::synthesis::Constraints;
/// let c = Constraints::default()
///     .with_full_rotation()
///     .with_transmission("beta", "gamma", 30f64.to_radians())
///     .with_link_ratio(&["a", "b", "c", "d"], 6.0);
/// assert!(c.full_rotation);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Constraints {
    /// The (single) input must turn fully on the candidate's assembly mode: a sweep over one
    /// turn from the first target closes on the position it started from (a Grashof crank for
    /// a four-bar, found for any mechanism).
    pub full_rotation: bool,
    /// Transmission angle to report and bound (over the motion checked: from the first to the
    /// last target, or the whole turn with [`Constraints::full_rotation`]).
    pub transmission: Option<TransmissionBound>,
    /// Bound on a ratio of link lengths.
    pub link_ratio: Option<LinkRatioBound>,
}

impl Constraints {
    /// Requires [`Constraints::full_rotation`].
    pub fn with_full_rotation(mut self) -> Self {
        self.full_rotation = true;
        self
    }

    /// Reports the transmission angle between the angle columns `coupler` and `follower` and
    /// requires it to stay at least `min` radians.
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
}
