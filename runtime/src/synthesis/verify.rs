//! Verification of a locally solved design: a branch-safe sweep from the first target through
//! every other, in order, must reach each on the assembly mode the targets were solved on;
//! then the optional constraints. Every candidate a search returns went through this.

use super::candidate::{Candidate, Defect, FourBarClass, Origin};
use super::local::LocalReport;
use super::problem::ProblemOf;
use super::residuals::{Eval, value, wrap};
use super::resolve::Inputs;
use crate::analysis::column::jet_along;
use crate::analysis::{ColumnIndex, Jet};
use crate::dims::{Dims, KinState};
use crate::error::Error;
use crate::kinds::QuantityKind;
use crate::mechanism::kernel::{KinOf, Q, SensKernel};
use crate::metrics::{FourBarLinks, grashof, transmission_angle, transmission_range};
use crate::paths::outcome::SweepStop;
use crate::paths::sweep::SweepOf;
use std::borrow::Cow;
use std::f64::consts::TAU;

/// Samples of each sweep between consecutive targets (the transmission angle is their
/// minimum, with the targets'), and of a turn checked for full rotation.
const STRETCH_SAMPLES: usize = 9;
const TURN_SAMPLES: usize = 73;

/// Two positions are the same assembly mode when every unknown agrees to this, relative to
/// its size (angles modulo a turn): far above the solves' tolerances, far below the distance
/// between distinct assembly modes of a design that is not near singular.
const SAME_POSITION: f64 = 1e-6;

/// Two free inputs are one when they differ by this, relative to the inputs' span: far above
/// the rounding of the solves that found them, far below the distance between targets.
const SAME_INPUT: f64 = 1e-9;

/// `size` is the unit of a length (the targets' size); `m` tells the unknowns' kinds.
fn same_position<K: SensKernel>(m: &K, a: &[f64], b: &[f64], size: f64) -> bool {
    (0..a.len()).all(|u| match m.unknown_kind(u) {
        QuantityKind::Angle => wrap(a[u] - b[u]).abs() <= SAME_POSITION,
        _ => (a[u] - b[u]).abs() <= SAME_POSITION * (size + b[u].abs()),
    })
}

/// The free inputs as one monotone motion: themselves if strictly monotone; where the motion
/// `wraps` (an angle input free over at least a turn), also in cyclic order within less than a
/// turn (a crank passing its zero between two targets), unwrapped by whole turns, in the sense
/// that turns less; `None` otherwise (an order defect). Over a range shorter than a turn a
/// cyclic step passes the inputs the range leaves out (from 2.8 forward to 0.2 over `[0, 3]`
/// turned the crank through 3 to 2 pi), so there the inputs must be monotone as they are.
/// An angle input is periodic in every declaration of a mechanism that turns by it (its sines
/// and cosines); where it is not (a gear ratio that is no integer), the sweep to the unwrapped
/// input does not reach the solved position, and the candidate has a branch defect instead.
///
/// `repeat[k]` says that target `k + 1` is target `k` again: its input may then equal the
/// one before, and within [`SAME_INPUT`] of the inputs' span (of a radian at least, for an
/// angle) it is that input, whichever way the rounding of the two solves falls (two apart by
/// 2e-16 passed, equal ones were an order defect). Distinct targets are met at distinct inputs.
/// Inputs that are all one are no motion: an order defect.
fn in_order(x: &[f64], repeat: &[bool], angle: bool, wraps: bool) -> Option<Vec<f64>> {
    let span = x.iter().map(|v| (v - x[0]).abs()).fold(0.0, f64::max);
    let tol = SAME_INPUT * if angle { span.max(1.0) } else { span };
    let mut x = x.to_vec();
    for k in 1..x.len() {
        if repeat[k - 1] && (x[k] - x[k - 1]).abs() <= tol {
            x[k] = x[k - 1];
        }
    }
    if x.windows(2).all(|w| w[0] == w[1]) {
        return None;
    }
    // A step forward: positive, or none at a repeated target.
    let forward = |k: usize, d: f64| d > 0.0 || (d == 0.0 && repeat[k]);
    let monotone = |s: f64| x.windows(2).enumerate().all(|(k, w)| forward(k, s * (w[1] - w[0])));
    if monotone(1.0) || monotone(-1.0) {
        return Some(x);
    }
    if !wraps {
        return None;
    }
    [1.0, -1.0]
        .iter()
        .filter_map(|&s| {
            let steps: Vec<f64> = x.windows(2).map(|w| (s * (w[1] - w[0])).rem_euclid(TAU)).collect();
            let total: f64 = steps.iter().sum();
            (steps.iter().enumerate().all(|(k, &d)| forward(k, d)) && total < TAU).then_some((s, steps, total))
        })
        .min_by(|a, b| a.2.total_cmp(&b.2))
        .map(|(s, steps, _)| {
            let mut at = x[0];
            std::iter::once(at)
                .chain(steps.iter().map(|d| {
                    at += s * d;
                    at
                }))
                .collect()
        })
}

/// The Grashof class of the four-bar `[ground, input, coupler, output]` and its smallest
/// transmission angle over the input's range (see [`FourBarClass`]); `None` where the lengths
/// are no four-bar that moves (one not positive, or one at least as long as the other three
/// together).
pub(crate) fn four_bar_class(lengths: [f64; 4]) -> Option<FourBarClass> {
    let [d, a, b, c] = lengths;
    let g = grashof(FourBarLinks { ground: d, input: a, coupler: b, output: c }).ok()?;
    let min_transmission = if g.input_turns { min_transmission_of_turning(lengths) } else { 0.0 };
    Some(FourBarClass { class: g.class, margin: g.margin, min_transmission })
}

/// The smallest transmission angle of a four-bar `[ground, input, coupler, output]` whose input
/// turns fully (lengths finite and positive, as `grashof` checked).
///
/// The distance from the input's tip to the output's pivot runs from |d - a| to d + a, and the
/// cosine of the transmission angle is linear in its square: the acute angle is smallest at one
/// of the two ends. The lengths are taken in units of the largest one's power of two (exact):
/// their squares left the range of `f64` beyond about `1e154` (and lost their digits below about
/// `1e-154`), the cosine came out NaN, read as 1, and the angle as 0, in no unit but those.
fn min_transmission_of_turning(lengths: [f64; 4]) -> f64 {
    let unit = crate::number::pow2_at_most(lengths.iter().copied().fold(0.0, f64::max));
    let [d, a, b, c] = lengths.map(|v| v / unit);
    let acute = |e: f64| ((b * b + c * c - e * e) / (2.0 * b * c)).abs().min(1.0).acos();
    acute(d - a).min(acute(d + a))
}

/// The fraction of the straight path `from + s dir` at each of the inputs `xs`: the projection of
/// `x - from` on `dir` over `|dir|^2`; empty where `dir` is zero or not finite. Taken in units of
/// the largest component of `dir` (a power of two, exact): a length input's range squared left
/// the range of `f64` beyond about `1e154` of the unit (every fraction 0, not increasing), and
/// the smallest transmission angle fell back to the samples' smallest.
fn path_fractions<'a>(xs: impl Iterator<Item = &'a [f64]>, from: &[f64], dir: &[f64]) -> Vec<f64> {
    let largest = dir.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    if !(largest > 0.0 && largest.is_finite()) {
        return Vec::new();
    }
    let unit = crate::number::pow2_at_most(largest);
    let dir: Vec<f64> = dir.iter().map(|d| d / unit).collect();
    let norm2: f64 = dir.iter().map(|d| d * d).sum();
    xs.map(|x| x.iter().zip(from).zip(&dir).map(|((x, a), d)| (x - a) / unit * d).sum::<f64>() / norm2).collect()
}

impl<K: SensKernel> ProblemOf<K> {
    /// The candidate of the local solution `z` (evaluated as `e`), verified. An error only where
    /// the kernel refuses `z`'s parameters (which `params` sizes to its count).
    pub(crate) fn verify(
        &self,
        origin: Origin,
        start: usize,
        z: Vec<f64>,
        e: Eval<Q<K>>,
        local: LocalReport,
    ) -> Result<Candidate, Error> {
        let params = self.params(&z);
        self.base.with_params(&params, |m| self.verify_with(m, origin, start, z, e, local, params.clone()))
    }

    /// The smallest transmission angle between the angle columns `c` and `f` along `run`, the
    /// states of one verifying sweep over a straight path of the inputs: located between the
    /// samples ([`transmission_range`]: at the roots of the relative angle's velocity analog,
    /// each evaluated by a short branch-safe sweep from the nearest sample), since the samples
    /// alone overstate a minimum that lies between them (by 0.03 degrees for a crank-rocker
    /// whose turn, sampled every five degrees, passes its extremes 2.5 degrees away), and a
    /// design just below the bound would pass. The samples' smallest where it cannot be located.
    fn least_transmission(&self, m: &K, run: &[KinOf<K>], c: ColumnIndex, f: ColumnIndex) -> f64 {
        let sampled = run.iter().map(|k| transmission_angle(value(k, c), value(k, f))).fold(f64::INFINITY, f64::min);
        let (Some(first), Some(last)) = (run.first(), run.last()) else { return sampled };
        // The path x(s) = from + s dir, s from 0 to 1.
        let from = first.x();
        let dir: Vec<f64> = last.x().iter().zip(from).map(|(b, a)| b - a).collect();
        let s = path_fractions(run.iter().map(|k| k.x()), from, &dir);
        if run.len() < 2 || s.is_empty() || !s.windows(2).all(|w| w[1] > w[0]) {
            return sampled;
        }
        let jets = |col| run.iter().zip(&s).map(|(k, &s)| jet_along(col, k, s, &dir)).collect::<Vec<_>>();
        let eval = |t: f64| -> Result<(Jet, Jet), Error> {
            let i = s.partition_point(|&v| v < t).min(run.len() - 1);
            let j = if i > 0 && (t - s[i - 1]).abs() <= (s[i] - t).abs() { i - 1 } else { i };
            let (mut x0, mut x, mut q) = (self.base.dims().x(), self.base.dims().x(), self.base.dims().q());
            x0.as_mut().copy_from_slice(run[j].x());
            x.as_mut().iter_mut().zip(from.iter().zip(&dir)).for_each(|(x, (a, d))| *x = a + t * d);
            q.as_mut().copy_from_slice(run[j].q());
            let r = SweepOf::<&K, KinOf<K>>::over(m, x0, x, 2, q)?.with_config(self.sweep).run();
            match r.states.last() {
                Some(k) if r.is_completed() => Ok((jet_along(c, k, t, &dir), jet_along(f, k, t, &dir))),
                _ => Err(Error::InvalidArgument("the transmission angle's minimum could not be located".into())),
            }
        };
        transmission_range(&jets(c), &jets(f), eval).map_or(sampled, |r| r.min.angle.min(sampled))
    }

    /// [`ProblemOf::verify`] on `m`, the mechanism with the parameters `params` of `z`.
    #[allow(clippy::too_many_arguments)]
    fn verify_with(
        &self,
        m: &K,
        origin: Origin,
        start: usize,
        z: Vec<f64>,
        e: Eval<Q<K>>,
        local: LocalReport,
        params: Vec<f64>,
    ) -> Candidate {
        let mut inputs = self.input_values(&z);
        let n = inputs.len();
        let mut defects = Vec::new();
        if matches!(self.inputs, Inputs::Free { .. }) && n > 1 {
            let free: Vec<f64> = inputs.iter().map(|x| x[0]).collect();
            let row = |k: usize| &self.targets[k * self.width..(k + 1) * self.width];
            let repeat: Vec<bool> = (1..n).map(|k| row(k) == row(k - 1)).collect();
            let angle = m.input_kind(0) == QuantityKind::Angle;
            // A turn to within the rounding of its ends: `(lo, lo + TAU)` is one whatever `lo`.
            let turn = |lo: f64, hi: f64| hi - lo >= TAU * (1.0 - SAME_INPUT);
            let wraps = angle && matches!(self.inputs, Inputs::Free { lo, hi } if turn(lo, hi));
            match in_order(&free, &repeat, angle, wraps) {
                Some(x) => inputs = Cow::Owned(x.into_iter().map(|v| self.input_point(v)).collect()),
                None => defects.push(Defect::Order),
            }
        }
        // The motion from target to target on the first target's assembly mode: the states of
        // each stretch swept (each a straight path of the inputs).
        let mut runs: Vec<Vec<KinOf<K>>> = Vec::new();
        for k in 1..n {
            // No motion between two targets at one input: the same position, or two assembly
            // modes at once (each target met on its own, no sweep to tell).
            if inputs[k].as_ref() == inputs[k - 1].as_ref() {
                if same_position(m, e.qs[k - 1].as_ref(), e.qs[k].as_ref(), self.length) {
                    continue;
                }
                defects.push(Defect::Branch { target: k });
                break;
            }
            let run = SweepOf::<&K, KinOf<K>>::over(
                m,
                inputs[k - 1].clone(),
                inputs[k].clone(),
                STRETCH_SAMPLES,
                e.qs[k - 1].clone(),
            )
            .map(|s| s.with_config(self.sweep).run());
            let defect = match run {
                Ok(r) => match (&r.stop, r.states.last()) {
                    (SweepStop::Completed, Some(last)) => {
                        let reached = same_position(m, last.q(), e.qs[k].as_ref(), self.length);
                        if self.checks.transmission.is_some() {
                            runs.push(r.states.clone());
                        }
                        (!reached).then_some(Defect::Branch { target: k })
                    }
                    (SweepStop::LimitPosition(ev), _) => {
                        Some(Defect::Circuit { target: k, at: ev.x.first().copied().unwrap_or(f64::NAN) })
                    }
                    (SweepStop::SingularCrossing(_), _) => Some(Defect::Branch { target: k }),
                    _ => Some(Defect::NoAssembly { target: k }),
                },
                Err(_) => Some(Defect::NoAssembly { target: k }),
            };
            if let Some(d) = defect {
                defects.push(d);
                break;
            }
        }
        if self.checks.full_rotation {
            let dir = if n > 1 && inputs[n - 1][0] < inputs[0][0] { -1.0 } else { 1.0 };
            let mut to = inputs[0].clone();
            to.as_mut().iter_mut().for_each(|x| *x += dir * TAU);
            let run = SweepOf::<&K, KinOf<K>>::over(m, inputs[0].clone(), to, TURN_SAMPLES, e.qs[0].clone())
                .map(|s| s.with_config(self.sweep).run());
            match run {
                Ok(r)
                    if r.is_completed()
                        && r.states.last().is_some_and(|l| same_position(m, l.q(), e.qs[0].as_ref(), self.length)) =>
                {
                    runs = vec![r.states];
                }
                _ => defects.push(Defect::NoFullRotation),
            }
        }
        let mut min_transmission = None;
        if let Some((c, f, min)) = self.checks.transmission {
            let at_targets =
                e.qs.iter().zip(inputs.iter()).filter_map(|(q, x)| m.kinematics_at(x, q, &self.newton).ok());
            let angle = runs
                .iter()
                .map(|run| self.least_transmission(m, run, c, f))
                .chain(at_targets.map(|k| transmission_angle(value(&k, c), value(&k, f))))
                .fold(f64::INFINITY, f64::min);
            if angle.is_finite() {
                min_transmission = Some(angle);
                if angle < min {
                    defects.push(Defect::Transmission { min: angle });
                }
            }
        }
        if let Some((idx, max)) = &self.checks.link_ratio {
            let lengths: Vec<f64> = idx.iter().map(|&i| params[i].abs()).collect();
            let ratio =
                lengths.iter().copied().fold(0.0, f64::max) / lengths.iter().copied().fold(f64::INFINITY, f64::min);
            // A NaN ratio (a zero or non-finite link) is a violation too.
            if !matches!(ratio.partial_cmp(max), Some(std::cmp::Ordering::Less | std::cmp::Ordering::Equal)) {
                defects.push(Defect::LinkRatio { ratio });
            }
        }
        let four_bar =
            self.checks.four_bar.and_then(|[d, a, b, c]| four_bar_class([d, a, b, c].map(|i| params[i].abs())));
        let errors: Vec<f64> = e.r.chunks(self.width).map(|c| crate::number::norm_of(c.iter().copied())).collect();
        let max_error = errors.iter().copied().fold(0.0, f64::max);
        // Last among the checks: the motion's defects say more of a design than its distance
        // from the targets, and the rejections count each candidate by its first.
        if let Some(max) = self.checks.max_error
            // A NaN error is a miss too.
            && let Some(target) = errors.iter().position(|e| e.is_nan() || *e > max)
        {
            defects.push(Defect::Miss { target, error: errors[target] });
        }
        // The root mean square as a norm over `sqrt(n)` (the squares of errors near the
        // largest `f64` overflow). Where the norm itself overflows (errors of 1e308 at two
        // targets), each error over `sqrt(n)` first: the mean of finite errors is finite, where
        // `inf` was written for it.
        let root_n = (n as f64).sqrt();
        let mut rms_error = crate::number::norm_of(errors.iter().copied()) / root_n;
        if rms_error.is_infinite() && max_error.is_finite() {
            rms_error = crate::number::norm_of(errors.iter().map(|e| e / root_n));
        }
        let placement = self.placement.map(|_| {
            let at = self.vars.len() + self.free_inputs();
            [z[at], z[at + 1], z[at + 2], z[at + 3]]
        });
        Candidate {
            start,
            origin,
            values: z[..self.vars.len()].to_vec(),
            params,
            inputs: inputs.iter().map(|x| x.as_ref().to_vec()).collect(),
            placement,
            positions: e.qs.iter().map(|q| q.as_ref().to_vec()).collect(),
            errors,
            max_error,
            rms_error,
            defects,
            min_transmission,
            four_bar,
            local,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{four_bar_class, in_order};
    use crate::metrics::GrashofClass;
    use std::f64::consts::TAU;

    /// The crank-rocker ground 4, input 1, coupler 3.5, output 3 has its input along the ground
    /// line where the input's tip is 3 and 5 from the output's pivot: by the law of cosines the
    /// coupler and output meet there at `acos(12.25 / 21) = acos(7 / 12)` and
    /// `acos(-3.75 / 21) = acos(-5 / 28)`, acute `acos(5 / 28)`, so its smallest transmission
    /// angle is `acos(7 / 12)`, in any unit. With lengths near `1e160` or beyond (their squares
    /// overflow) or near `1e-160` and below (their squares underflow) it read 0, a dead point.
    ///
    /// Tolerance: the lengths scaled by a power of ten carry a rounding each, the cosine a few
    /// more, about `1e-15` with `acos`'s slope (`1 / sin`, 1.23) there; `1e-14` keeps a factor
    /// of ten over it.
    #[test]
    fn the_smallest_transmission_angle_of_a_turning_input_is_the_same_in_any_unit() {
        let want = (7.0f64 / 12.0).acos();
        for scale in [1e-300, 1e-200, 1e-160, 1e-3, 1.0, 1e3, 1e160, 1e200, 1e300, 4e307] {
            let class = four_bar_class([4.0, 1.0, 3.5, 3.0].map(|v| v * scale)).expect("a four-bar that moves");
            assert_eq!(class.class, GrashofClass::CrankRocker, "{scale:e}: {class:?}");
            assert!((class.min_transmission - want).abs() < 1e-14, "{scale:e}: {class:?}, want {want}");
        }
    }

    /// A target repeated is one input whichever way the rounding falls; inputs all one, or out
    /// of order by more than rounding, are an order defect; an angle may pass its zero.
    #[test]
    fn a_repeated_target_is_in_order_whichever_way_the_rounding_falls() {
        let repeat = [false, true, false];
        for noise in [2e-16, 0.0, -2e-16] {
            let x = [0.1, 0.5, 0.5 + noise, 0.9];
            for angle in [false, true] {
                assert_eq!(in_order(&x, &repeat, angle, angle), Some(vec![0.1, 0.5, 0.5, 0.9]), "{noise} {angle}");
                // Distinct targets at one input: an order defect, as it was.
                assert_eq!(in_order(&x, &[false; 3], angle, angle).is_some(), noise > 0.0, "{noise} {angle}");
            }
        }
        assert_eq!(in_order(&[0.3, 0.3, 0.3], &[true; 2], true, true), None);
        assert_eq!(in_order(&[0.1, 0.5, 0.4999, 0.9], &repeat, false, false), None);
        // Past the zero of a turn, with a repeat there: unwrapped.
        let x = [TAU - 0.2, TAU - 0.1, TAU - 0.1 + 1e-15, 0.1];
        let got = in_order(&x, &repeat, true, true).expect("in cyclic order");
        assert_eq!(got[1], got[2]);
        assert!((got[3] - (TAU + 0.1)).abs() < 1e-12, "{got:?}");
    }
}
