//! Tasks: what the mechanism must do, as targets for named columns (an output point, a body
//! angle, any unknown or output), met at prescribed input values ("timing") or at input values
//! the search chooses, in order along one monotone motion.

/// What one target component asks of the mechanism.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Channel {
    /// A point: the output columns `name.x` and `name.y` (two components per target).
    Point(String),
    /// An angle (an unknown or output column): its error is measured modulo a turn.
    Angle(String),
    /// Any other scalar column (a slider's position, a scalar output).
    Value(String),
}

impl Channel {
    /// How many target values it takes.
    pub(crate) fn width(&self) -> usize {
        match self {
            Channel::Point(_) => 2,
            Channel::Angle(_) | Channel::Value(_) => 1,
        }
    }
}

/// When the targets must be met.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Timing {
    /// Not given yet: a task needs [`Task::timed`], [`Task::timed_inputs`] or [`Task::untimed`].
    Unset,
    /// The input values at each target (one row of `NI` values per target).
    Prescribed(#[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))] Vec<Vec<f64>>),
    /// The input value of each target is a variable of the search, within `[lo, hi]`; the targets
    /// must be met in order along one monotone motion (a mechanism with one input).
    Free {
        /// Lower bound of the input values.
        #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
        lo: f64,
        /// Upper bound of the input values.
        #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
        hi: f64,
    },
}

/// Bounds of the placement variables of a path (a similarity of the plane applied to the
/// mechanism's points and angles: a translation, a rotation and a scale), for fitting a shape
/// wherever, however turned and at whatever size it may be made.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PlacementBounds {
    /// Range of the translation's x.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub dx: (f64, f64),
    /// Range of the translation's y.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub dy: (f64, f64),
    /// Range of the rotation (radians).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub angle: (f64, f64),
    /// Range of the scale (positive).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub scale: (f64, f64),
}

impl PlacementBounds {
    /// A translation within `dx` and `dy` only (rotation 0, scale 1).
    pub fn translation(dx: (f64, f64), dy: (f64, f64)) -> Self {
        PlacementBounds { dx, dy, angle: (0.0, 0.0), scale: (1.0, 1.0) }
    }

    /// Also a rotation within `angle` (radians).
    pub fn with_rotation(mut self, angle: (f64, f64)) -> Self {
        self.angle = angle;
        self
    }

    /// Also a scale within `scale` (positive).
    pub fn with_scale(mut self, scale: (f64, f64)) -> Self {
        self.scale = scale;
        self
    }
}

/// A synthesis task: channels (what is measured), one row of target values per target, the
/// timing, and optionally a free placement.
///
/// ```
/// use kinloop_runtime::synthesis::Task;
/// // A coupler point through three points at given crank angles.
/// let task = Task::path("p", [[1.0, 2.0], [1.5, 2.2], [2.0, 2.1]]).timed([0.0, 0.5, 1.0]);
/// assert_eq!(task.len(), 3);
/// ```
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Task {
    /// What each target's values are values of, in order.
    pub channels: Vec<Channel>,
    /// One row per target: the channels' values, in order (a point contributes x then y).
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub targets: Vec<Vec<f64>>,
    /// When the targets are to be met.
    pub timing: Timing,
    /// A free placement of the mechanism (path and motion tasks), or none.
    pub placement: Option<PlacementBounds>,
    /// Weight of every component of each channel (default 1): e.g. the angle of a motion task
    /// against its point, in length units per radian.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde"))]
    pub weights: Vec<f64>,
}

impl Task {
    /// A task from its parts (timing unset, no placement, unit weights).
    pub fn new(channels: Vec<Channel>, targets: Vec<Vec<f64>>) -> Self {
        let weights = vec![1.0; channels.len()];
        Task { channels, targets, timing: Timing::Unset, placement: None, weights }
    }

    /// Path generation: the output point `point` (its columns `point.x`, `point.y`) through
    /// `targets`, in order. Give the timing next.
    pub fn path(point: impl Into<String>, targets: impl IntoIterator<Item = [f64; 2]>) -> Self {
        Task::new(vec![Channel::Point(point.into())], targets.into_iter().map(|t| t.to_vec()).collect())
    }

    /// Path fitting: [`Task::path`] through many samples of a curve, usually with
    /// [`Task::untimed`] and [`Task::with_placement`].
    pub fn fit(point: impl Into<String>, samples: impl IntoIterator<Item = [f64; 2]>) -> Self {
        Task::path(point, samples)
    }

    /// Motion generation: poses `[x, y, angle]` of the point `point` and of the angle column
    /// `angle` (a body's angle: an unknown or an output), reached in order. Give the timing next.
    pub fn motion(
        point: impl Into<String>,
        angle: impl Into<String>,
        poses: impl IntoIterator<Item = [f64; 3]>,
    ) -> Self {
        Task::new(
            vec![Channel::Point(point.into()), Channel::Angle(angle.into())],
            poses.into_iter().map(|t| t.to_vec()).collect(),
        )
    }

    /// Function generation: the column `output` (an unknown or an output) takes the value `y`
    /// at the input `x`, for each pair: timed by the pairs. An angle column's errors are
    /// measured modulo a turn. An offset between the function's and the mechanism's zero is a
    /// parameter of the declaration (e.g. `output psi = gamma - gamma0`), a design variable
    /// like any other.
    pub fn function(output: impl Into<String>, pairs: impl IntoIterator<Item = (f64, f64)>) -> Self {
        let (xs, ys): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
        let mut t = Task::new(vec![Channel::Value(output.into())], ys.into_iter().map(|y| vec![y]).collect());
        t.timing = Timing::Prescribed(xs.into_iter().map(|x| vec![x]).collect());
        t
    }

    /// The targets are met at these values of the (single) input, one per target.
    pub fn timed(mut self, inputs: impl IntoIterator<Item = f64>) -> Self {
        self.timing = Timing::Prescribed(inputs.into_iter().map(|x| vec![x]).collect());
        self
    }

    /// The targets are met at these input values, one row of all inputs per target.
    pub fn timed_inputs(mut self, inputs: Vec<Vec<f64>>) -> Self {
        self.timing = Timing::Prescribed(inputs);
        self
    }

    /// The input value of each target is free within `[lo, hi]` (a mechanism with one input);
    /// the targets must be met in order along one monotone motion (so with more than one target
    /// `lo < hi`). An angle input free over at least a turn may pass from `hi` back to `lo` (a
    /// crank passing its zero); over a shorter range the motion stays within it.
    pub fn untimed(mut self, lo: f64, hi: f64) -> Self {
        self.timing = Timing::Free { lo, hi };
        self
    }

    /// A free placement of the mechanism within `bounds`: its points are moved by
    /// `p -> d + s R(angle) p` and its angles turned by `angle` before they are compared with
    /// the targets (four more variables of the search).
    pub fn with_placement(mut self, bounds: PlacementBounds) -> Self {
        self.placement = Some(bounds);
        self
    }

    /// Weights of the channels' components, one per channel (default 1).
    pub fn with_weights(mut self, weights: Vec<f64>) -> Self {
        self.weights = weights;
        self
    }

    /// Number of targets.
    pub fn len(&self) -> usize {
        self.targets.len()
    }

    /// Whether there is no target.
    pub fn is_empty(&self) -> bool {
        self.targets.is_empty()
    }
}

/// `n` precision points at Chebyshev spacing between `lo` and `hi`:
/// `(lo + hi) / 2 - (hi - lo) / 2 cos((2j - 1) pi / 2n)` for `j = 1..=n`, in order from `lo`
/// to `hi`: increasing where `lo < hi`, decreasing where `lo > hi`.
/// They minimise the largest structural error of a function interpolated at them
/// (Freudenstein's choice of precision points in function generation).
///
/// Errors: those of [`chebyshev_points`](super::classical::chebyshev_points), which this is:
/// `n == 0` or more than memory holds, an end not finite, `lo == hi`, or a range too narrow for
/// `n` distinct doubles at Chebyshev spacing.
///
/// ```
/// use kinloop_runtime::synthesis::chebyshev;
/// let x = chebyshev(1.0, 2.0, 3)?;
/// assert!((x[0] - 1.0669872981077808).abs() < 1e-15 && (x[1] - 1.5).abs() < 1e-15);
/// // From 2 to 1: decreasing.
/// let back = chebyshev(2.0, 1.0, 3)?;
/// assert!((back[0] - 1.9330127018922192).abs() < 1e-15 && back[0] > back[1] && back[1] > back[2]);
/// # Ok::<(), kinloop_runtime::synthesis::classical::ClassicalError>(())
/// ```
pub fn chebyshev(lo: f64, hi: f64, n: usize) -> Result<Vec<f64>, super::classical::ClassicalError> {
    super::classical::chebyshev_points(n, lo, hi)
}

#[cfg(test)]
mod tests {
    use super::chebyshev;

    /// Five points on `[0.2, 3]` against the closed form written out, and bad arguments as
    /// errors: the largest `usize` overflowed `2 n` (a panic), a NaN end gave NaN points, no
    /// point an empty list.
    #[test]
    fn chebyshev_spacing_and_its_bad_arguments() {
        let x = chebyshev(0.2, 3.0, 5).unwrap();
        for (j, v) in x.iter().enumerate() {
            let want = 1.6 - 1.4 * ((2 * j + 1) as f64 * std::f64::consts::PI / 10.0).cos();
            // A few roundings of values near 3.
            assert!((v - want).abs() < 4.0 * f64::EPSILON * 3.0, "{j}: {v} vs {want}");
        }
        for (lo, hi, n) in
            [(0.0, 1.0, usize::MAX), (0.0, 1.0, 0), (f64::NAN, 1.0, 3), (0.0, f64::INFINITY, 3), (1.0, 1.0, 2)]
        {
            assert!(chebyshev(lo, hi, n).is_err(), "{lo} {hi} {n}");
        }
    }
}
