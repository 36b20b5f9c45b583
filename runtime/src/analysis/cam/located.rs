//! A cam's checks located between the samples ([`cam_extremes`], [`flat_face_extremes`]); see
//! the [`cam`](super) module's documentation, "Between the samples".

use super::plane::{apply, length_unit, norm, per_unit, quarter, rotate, scale, sub};
use super::{FlatFace, FollowerSample, cam_profile, flat_face_profile};
use crate::analysis::extremes::maximize;
use crate::error::Error;
use crate::number::Count;

/// The agreement of an interval's jets (a fraction of its change) below which it counts as
/// resolved: a smooth law sampled every degree agrees to some 1e-5, a law whose feature is
/// narrower than the interval fails it by a factor of ten or more.
const RESOLVED: f64 = 1e-3;

/// Most points added between the samples to resolve the motion: past it, the rest of the
/// intervals are taken as they are.
const MAX_POINTS: usize = 1 << 18;

/// Most halvings of one sample interval: an interval with a corner of the motion (a kink, where
/// the velocity analog jumps) never resolves, and is halved to a billionth of its width.
const MAX_DEPTH: u32 = 30;

/// Most local maxima of one quantity refined by Brent's search: those whose refinement could
/// reach the best point's value, largest first.
const MAX_REFINED: usize = 8;

/// A check's extreme value and where it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Located {
    /// The input there (the samples' parameter: the cam shaft's input).
    pub x: f64,
    /// The quantity's value there.
    pub value: f64,
}

/// A roller's (or knife edge's) cam's checks located between the samples ([`cam_extremes`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CamExtremes {
    /// The largest pressure angle (radians).
    pub max_pressure_angle: Located,
    /// The smallest radius of curvature of the pitch curve where it is convex: the sharpest
    /// point of the profile, less the roller's radius. `None` where it is nowhere convex.
    pub min_convex_radius: Option<Located>,
    /// The roller's radius the checks were made for.
    pub roller: f64,
}

impl CamExtremes {
    /// Whether the roller undercuts the profile somewhere: the pitch curve's smallest convex
    /// radius of curvature not above the roller's (see
    /// [`CamProfile::undercut`](super::CamProfile::undercut)).
    pub fn undercut(&self) -> bool {
        self.min_convex_radius.is_some_and(|r| r.value <= self.roller)
    }
}

/// A flat-faced follower's cam's checks located between the samples ([`flat_face_extremes`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatFaceExtremes {
    /// The largest pressure angle (radians).
    pub max_pressure_angle: Located,
    /// The smallest radius of curvature of the profile: zero or negative where the face's
    /// envelope has a cusp (see [`FlatFaceProfile::not_convex`](super::FlatFaceProfile::not_convex)).
    pub min_radius: Located,
    /// The smallest offset of the contact along the face.
    pub min_offset: Located,
    /// The largest offset of the contact along the face.
    pub max_offset: Located,
}

impl FlatFaceExtremes {
    /// The least width of the face: the largest offset less the smallest.
    pub fn face_width(&self) -> f64 {
        self.max_offset.value - self.min_offset.value
    }

    /// Whether the profile is convex everywhere (its smallest radius of curvature positive).
    pub fn convex(&self) -> bool {
        self.min_radius.value > 0.0
    }
}

/// The checks of [`cam_profile`]'s cam (the samples, the `pivot` and the `roller` as given
/// there) located between the samples: `inputs` are the samples' inputs (increasing), and
/// `eval` gives the follower's sample at any input between the first and the last, on the
/// samples' branch. See the [`cam`](super) module's documentation, "Between the samples".
///
/// Errors: those of [`cam_profile`] (at the samples, and at the points evaluated between them),
/// `inputs` not one per sample or not increasing, and those of `eval`.
///
/// ```
/// use kinloop_runtime::analysis::cam::{FollowerSample, cam_extremes, cam_profile};
/// // A radial follower lifted by s = 2 (1 - cos phi) above a base circle of 10, sampled at
/// // quarter turns: tan(pressure angle) = s' / (10 + s) = 2 sin phi / (12 - 2 cos phi) is
/// // largest where cos phi = 1/6, between the samples.
/// let at = |phi: f64| {
///     let (s, ds, d2s) = (2.0 * (1.0 - phi.cos()), 2.0 * phi.sin(), 2.0 * phi.cos());
///     FollowerSample { cam: [phi, 1.0, 0.0], point: [[0.0, 10.0 + s], [0.0, ds], [0.0, d2s]], direction: [0.0, 1.0] }
/// };
/// let inputs: Vec<f64> = (0..5).map(|k| k as f64 * std::f64::consts::FRAC_PI_2).collect();
/// let samples: Vec<FollowerSample> = inputs.iter().map(|&phi| at(phi)).collect();
/// let sampled = cam_profile(&samples, [0.0, 0.0], 1.0)?.max_pressure_angle().1;
/// let located = cam_extremes(&inputs, &samples, [0.0, 0.0], 1.0, |phi| Ok(at(phi)))?;
/// let phi = (1.0f64 / 6.0).acos();
/// let best = (2.0 * phi.sin()).atan2(12.0 - 2.0 * phi.cos());
/// assert!((located.max_pressure_angle.value - best).abs() < 1e-15 && sampled < best - 1e-4);
/// assert!((located.max_pressure_angle.x - phi).abs() < 1e-7);
/// assert!(!located.undercut());
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn cam_extremes(
    inputs: &[f64],
    samples: &[FollowerSample],
    pivot: [f64; 2],
    roller: f64,
    mut eval: impl FnMut(f64) -> Result<FollowerSample, Error>,
) -> Result<CamExtremes, Error> {
    // The pressure angle and the pitch curve's curvature (0 where it is straight; positive
    // where convex).
    let checks = |s: &FollowerSample| {
        let cam = cam_profile(std::slice::from_ref(s), pivot, roller)?;
        Ok([cam.pressure_angle[0], 1.0 / cam.pitch_radius[0]])
    };
    let [alpha, curvature] = located(inputs, samples, pivot, &mut eval, &checks)?;
    let min_convex_radius = (curvature.value > 0.0).then(|| Located { x: curvature.x, value: 1.0 / curvature.value });
    Ok(CamExtremes { max_pressure_angle: alpha, min_convex_radius, roller })
}

/// The checks of [`flat_face_profile`]'s cam (the samples, the `pivot` and the `face` as given
/// there) located between the samples, as [`cam_extremes`] locates a roller's: `inputs` are the
/// samples' inputs (increasing), and `eval` gives the follower's sample at any input between
/// the first and the last, on the samples' branch.
///
/// Errors: those of [`flat_face_profile`] (at the samples, and at the points evaluated between
/// them), `inputs` not one per sample or not increasing, and those of `eval`.
pub fn flat_face_extremes(
    inputs: &[f64],
    samples: &[FollowerSample],
    pivot: [f64; 2],
    face: FlatFace,
    mut eval: impl FnMut(f64) -> Result<FollowerSample, Error>,
) -> Result<FlatFaceExtremes, Error> {
    let checks = |s: &FollowerSample| {
        let cam = flat_face_profile(std::slice::from_ref(s), pivot, face)?;
        Ok([cam.pressure_angle[0], -cam.radius[0], cam.offset[0], -cam.offset[0]])
    };
    let [alpha, radius, hi, lo] = located(inputs, samples, pivot, &mut eval, &checks)?;
    let negated = |l: Located| Located { value: -l.value, ..l };
    Ok(FlatFaceExtremes {
        max_pressure_angle: alpha,
        min_radius: negated(radius),
        min_offset: negated(lo),
        max_offset: hi,
    })
}

/// The largest value of each of the `K` quantities `checks` gives of a follower's sample, over
/// the range of `inputs`, located as the [`cam`](super) module's documentation says.
fn located<const K: usize>(
    inputs: &[f64],
    samples: &[FollowerSample],
    pivot: [f64; 2],
    eval: &mut dyn FnMut(f64) -> Result<FollowerSample, Error>,
    checks: &dyn Fn(&FollowerSample) -> Result<[f64; K], Error>,
) -> Result<[Located; K], Error> {
    let bad = |m: String| Err(Error::InvalidArgument(format!("cam extremes: {m}")));
    if inputs.len() != samples.len() || samples.is_empty() {
        return bad(format!("{} for {}", Count(inputs.len(), "input"), Count(samples.len(), "sample")));
    }
    if let Some(w) = inputs.windows(2).find(|w| w[0].partial_cmp(&w[1]) != Some(std::cmp::Ordering::Less)) {
        return bad(format!("the inputs must increase (found {} then {})", w[0], w[1]));
    }
    let (xs, points) = resolved(inputs, samples, pivot, eval)?;
    let values: Vec<[f64; K]> = points.iter().map(checks).collect::<Result<_, _>>()?;
    let mut best = [Located { x: f64::NAN, value: f64::NAN }; K];
    for (q, best) in best.iter_mut().enumerate() {
        let v: Vec<f64> = values.iter().map(|v| v[q]).collect();
        let top = (0..v.len()).fold(0, |b, j| if v[j] > v[b] { j } else { b });
        *best = Located { x: xs[top], value: v[top] };
        let last = v.len() - 1;
        // Local maxima whose refinement may reach the best: a smooth peak between a point and
        // its neighbours lies above the point by at most its rise over the lower neighbour.
        let rise = |j: usize| {
            let lower = [j.checked_sub(1), (j < last).then_some(j + 1)].into_iter().flatten().map(|i| v[i]);
            v[j] - lower.fold(v[j], f64::min)
        };
        let mut candidates: Vec<usize> = (0..v.len())
            .filter(|&j| (j == 0 || v[j] >= v[j - 1]) && (j == last || v[j] >= v[j + 1]))
            .filter(|&j| v[j] + rise(j) >= v[top] && (j == top || rise(j) > 0.0))
            .collect();
        candidates.sort_by(|&a, &b| v[b].total_cmp(&v[a]));
        for j in candidates.into_iter().take(MAX_REFINED) {
            let (lo, hi) = (xs[j.saturating_sub(1)], xs[(j + 1).min(last)]);
            if lo >= hi {
                continue;
            }
            let (x, value) = maximize(lo, hi, |x| eval(x).and_then(|s| checks(&s)).map(|v| v[q]))?;
            if value > best.value {
                *best = Located { x, value };
            }
        }
    }
    Ok(best)
}

/// The samples and the points between them that resolve the motion (see the
/// [`cam`](super) module's documentation), in increasing input.
fn resolved(
    inputs: &[f64],
    samples: &[FollowerSample],
    pivot: [f64; 2],
    eval: &mut dyn FnMut(f64) -> Result<FollowerSample, Error>,
) -> Result<(Vec<f64>, Vec<FollowerSample>), Error> {
    let mut xs = vec![inputs[0]];
    let mut points = vec![samples[0]];
    let mut added = 0;
    for k in 1..samples.len() {
        // Depth-first over the halves, the right one on the stack below the left.
        let mut stack = vec![(inputs[k], samples[k], 0u32)];
        while let Some(&(b, sb, depth)) = stack.last() {
            let (a, sa) = (xs[xs.len() - 1], points[points.len() - 1]);
            let m = 0.5 * (a + b);
            if depth >= MAX_DEPTH || added >= MAX_POINTS || !(a < m && m < b) || agree(a, &sa, b, &sb, pivot) {
                stack.pop();
                xs.push(b);
                points.push(sb);
                continue;
            }
            let sm = eval(m)?;
            added += 1;
            // Both halves one level deeper: the right one's end below the middle on the stack.
            if let Some(right) = stack.last_mut() {
                right.2 = depth + 1;
            }
            stack.push((m, sm, depth + 1));
        }
    }
    Ok((xs, points))
}

/// The pitch curve's position, velocity and acceleration analogs in the cam's frame at the
/// sample `s` (see the [`cam`](super) module's documentation), in units of `unit`.
fn pitch_jet(s: &FollowerSample, pivot: [f64; 2], unit: f64) -> [[f64; 2]; 3] {
    let [theta, dtheta, d2theta] = s.cam;
    let [p, dp, d2p] = s.point;
    let q = per_unit(sub(p, pivot), unit);
    let (dq, d2q) = (per_unit(dp, unit), per_unit(d2p, unit));
    let dr = sub(dq, scale(dtheta, quarter(q)));
    let d2r = sub(
        sub(d2q, scale(d2theta, quarter(q))),
        [
            2.0 * dtheta * quarter(dq)[0] + dtheta * dtheta * q[0],
            2.0 * dtheta * quarter(dq)[1] + dtheta * dtheta * q[1],
        ],
    );
    let back = rotate(-theta);
    [apply(back, q), apply(back, dr), apply(back, d2r)]
}

/// Whether the pitch curve's jets at the ends of the interval from `a` to `b` agree (see the
/// [`cam`](super) module's documentation).
fn agree(a: f64, sa: &FollowerSample, b: f64, sb: &FollowerSample, pivot: [f64; 2]) -> bool {
    let h = b - a;
    let lengths = [sa, sb].into_iter().flat_map(|s| s.point.iter().flatten().chain(&pivot));
    let unit = length_unit(lengths);
    let ([r0, v0, w0], [r1, v1, w1]) = (pitch_jet(sa, pivot, unit), pitch_jet(sb, pivot, unit));
    let position = [
        r1[0] - r0[0] - 0.5 * h * (v0[0] + v1[0]) + h * h / 12.0 * (w1[0] - w0[0]),
        r1[1] - r0[1] - 0.5 * h * (v0[1] + v1[1]) + h * h / 12.0 * (w1[1] - w0[1]),
    ];
    let velocity = [v1[0] - v0[0] - 0.5 * h * (w0[0] + w1[0]), v1[1] - v0[1] - 0.5 * h * (w0[1] + w1[1])];
    let speed = 0.5 * h.abs() * (norm(v0) + norm(v1));
    let turning = 0.5 * h.abs() * (norm(w0) + norm(w1)) + speed;
    let fine = norm(position) <= RESOLVED * speed && norm(velocity) <= RESOLVED * turning;
    // Not finite (an overflow at a scale the unit misses): nothing better is known.
    fine || !(norm(position).is_finite() && norm(velocity).is_finite())
}
