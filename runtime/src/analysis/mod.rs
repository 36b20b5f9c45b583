//! Analysis helpers over sweeps and sampled signals: extremes, dwells, Fourier coefficients,
//! unbalance, a small optimiser.
//!
//! Two layers:
//!
//! * **Any smooth quantity** given as [`Jet`]s (value, first and second derivative at `x`):
//!   samples in increasing `x` plus an evaluator `FnMut(f64) -> Result<Jet, Error>` for points
//!   in between. Used directly for test signals and derived quantities:
//!   [`extremes()`](extremes::extremes), [`global_range`], [`dwells()`](dwell::dwells),
//!   [`fourier()`](fourier::fourier), [`unbalance()`](unbalance::unbalance), [`maximize`].
//! * **A mechanism's unknown or output column** over a sweep: [`Sampled`] runs a branch-safe
//!   sweep (one input, or several moving along a straight path) once and answers the same
//!   questions by column, given as the generated typed handle (`Name::COL.x_f`,
//!   `Name::COL.s2.x`; see [`Column`]), evaluating the generated analogs between samples,
//!   warm-started from the nearest sample so the refinement stays on the sweep's branch.
//!
//! | question | helper | how it is located |
//! |---|---|---|
//! | extreme positions, stroke, swing | [`SampledOf::extremes`], [`SampledOf::range`] | roots of the velocity analog (safeguarded Newton with the acceleration analog) |
//! | peak of a quantity without analog (e.g. an acceleration analog) | [`SampledOf::peak`] | Brent's derivative-free search between samples |
//! | dwells of a progressive output | [`SampledOf::dwells`] | extremes plus band crossings (see [`dwell`]) |
//! | harmonics over a cycle | [`SampledOf::fourier`] | trapezoidal rule, exact for trigonometric polynomials |
//! | residual unbalance `max |v - v_1|` | [`SampledOf::unbalance`] | extremes of the residual |
//! | a disc cam's pitch curve, profile, curvature and pressure angle from its follower's motion | [`cam::cam_profile`] | kinematic inversion of the positions and analogs |
//! | a flat-faced follower's cam: contact, curvature, offset along the face, pressure angle | [`cam::flat_face_profile`] | envelope of the face by inversion of the positions and analogs |
//! | a cam's largest pressure angle, sharpest point, undercut or cusp, between the samples | [`cam::cam_extremes`], [`cam::flat_face_extremes`] | the motion evaluated between the samples until resolved, then Brent's search |
//! | design optimisation without gradients | [`NelderMead`] (`minimize`, `minimize_boxed`) | Nelder–Mead simplex (in a box: MINUIT's sine transformation) |
//!
//! ```ignore
//! use kinloop_runtime::analysis::Sampled;
//! use std::f64::consts::TAU;
//! // `SliderCrank` stands for any mechanism declared with `kinloop::mechanism!` (here an offset
//! // slider-crank written by hand: crank 1, rod 3, offset 0.5, one unknown `x`).
//! let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
//! let turn = Sampled::sweep(&m, 0.0, TAU, 73, [3.9])?;       // every 5 degrees, one turn
//! let x = turn.range(X)?;                                  // dead centres, located exactly
//! let outer = (4.0f64.powi(2) - 0.25).sqrt();                 // crank and rod stretched
//! let inner = (2.0f64.powi(2) - 0.25).sqrt();                 // crank and rod folded
//! assert!((x.max.value - outer).abs() < 1e-12 && (x.min.value - inner).abs() < 1e-12);
//! assert!((x.max.x - 0.5f64.atan2(outer)).abs() < 1e-10);
//! assert!((x.span() - (outer - inner)).abs() < 1e-12);        // the stroke
//! let harmonics = turn.fourier(X, 4)?;                      // x = a0 + a1 cos phi + ...
//! assert!((harmonics.a[0] - 1.0).abs() < 1e-12);              // the crank's own cos phi
//! # Ok::<(), kinloop_runtime::Error>(())
//! ```

pub mod cam;
pub(crate) mod column;
#[cfg(test)]
pub(crate) mod demo;
pub mod dwell;
pub mod extremes;
pub mod fourier;
pub mod objective;
pub mod optimize;
pub mod rest;
mod sampled;
pub mod unbalance;

pub use column::{Column, ColumnIndex, ColumnOf};
pub(crate) use sampled::check_sampled_memory;
#[cfg(test)]
pub(crate) use sampled::sampled_bytes_each;
pub use sampled::{MAX_SEARCH_POINTS, Sampled, SampledOf, samples_to_search};

pub use dwell::{Dwell, dwells};
pub use extremes::{Extreme, GlobalRange, LocalExtreme, bracketed_root, extremes, global_range, maximize};
pub use fourier::{Fourier, fourier};
pub use optimize::{LevenbergMarquardt, Minimum, NelderMead, OptimizerStop};
pub use rest::{Rest, rests};
pub use unbalance::{Unbalance, unbalance};

use crate::error::Error;

/// The most samples an analysis evaluates at (the intervals of [`Jet::sample`], the samples of
/// a [`Sampled`] sweep and of
/// [`structural_error`](crate::synthesis::classical::structural_error)): more is refused with
/// an error instead of running for hours or collecting more than memory holds. A range cut into
/// `10^8` pieces is sampled every `1e-8` of its length, where a smooth quantity changes between
/// samples by a second-order term of about `1e-16` of its scale, the rounding of a double: more
/// samples resolve nothing more.
pub const MAX_SAMPLES: usize = 100_000_000;

/// `Err` naming `what` and the limit when `count` is beyond [`MAX_SAMPLES`].
pub(crate) fn check_sample_count(what: &str, count: usize) -> Result<(), String> {
    if count > MAX_SAMPLES {
        return Err(format!("{count} {what} asked for: at most {MAX_SAMPLES} are taken (`analysis::MAX_SAMPLES`)"));
    }
    Ok(())
}

/// A smooth quantity at one point: its value and its first and second derivatives with respect
/// to `x` (for a mechanism: position, velocity analog and acceleration analog at input `x`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Jet {
    /// The input value.
    pub x: f64,
    /// The quantity at `x`.
    pub value: f64,
    /// Its first derivative with respect to the input.
    pub d1: f64,
    /// Its second derivative with respect to the input.
    pub d2: f64,
}

impl Jet {
    /// `intervals + 1` equally spaced jets of `f` from `from` to `to` (both included).
    ///
    /// Errors: no interval, or more than [`MAX_SAMPLES`], or more jets than the 1 GiB of memory
    /// kept at most (2^25 jets), an end not finite (before `f` is called); the first error of `f`.
    ///
    /// ```
    /// use kinloop_runtime::analysis::Jet;
    /// let s = Jet::sample(|x| Ok(Jet { x, value: x * x, d1: 2.0 * x, d2: 2.0 }), 0.0, 1.0, 4)?;
    /// assert_eq!(s.len(), 5);
    /// assert_eq!(s[2].value, 0.25);
    /// # Ok::<(), kinloop_runtime::Error>(())
    /// ```
    pub fn sample(
        mut f: impl FnMut(f64) -> Result<Jet, Error>,
        from: f64,
        to: f64,
        intervals: usize,
    ) -> Result<Vec<Jet>, Error> {
        if intervals == 0 {
            return Err(Error::InvalidArgument("at least one interval is needed".into()));
        }
        check_sample_count("intervals", intervals).map_err(Error::InvalidArgument)?;
        if !(from.is_finite() && to.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "the ends of a sampled range must be finite, got {from} and {to}"
            )));
        }
        // Every jet is kept: within `MAX_SAMPLES`, 10^8 intervals would reserve 3.2 GB.
        let (jet_bytes, budget) = (size_of::<Jet>(), crate::paths::collected::MAX_COLLECTED_BYTES);
        let instead = format!(
            "give at most {} intervals (the jets that fit), or sample the range in parts",
            budget / jet_bytes - 1
        );
        crate::paths::collected::check_collected("`Jet::sample`", "jets", intervals + 1, jet_bytes, &instead)?;
        let mut jets = Vec::new();
        jets.try_reserve_exact(intervals + 1)
            .map_err(|e| Error::InvalidArgument(format!("{intervals} intervals: no room for their jets ({e})")))?;
        // Ends far apart near the largest f64 (`-1e308` to `1e308`) overflow `to - from`, which
        // made the first input NaN and the others infinite: weighted ends there instead.
        let wide = !(to - from).is_finite();
        let at = |i: usize| {
            let t = i as f64 / intervals as f64;
            if wide { (1.0 - t) * from + t * to } else { from + (to - from) * i as f64 / intervals as f64 }
        };
        for i in 0..=intervals {
            jets.push(f(if i == intervals { to } else { at(i) })?);
        }
        Ok(jets)
    }
}

#[cfg(test)]
mod tests {
    use super::demo::SliderCrank;
    use super::*;
    use crate::mechanism::Mechanism;
    use std::f64::consts::{PI, TAU};

    const X: Column<SliderCrank> = SliderCrank::COL.x;

    const M: SliderCrank = SliderCrank { r: 1.0, l: 2.5, e: 0.7 };

    /// The slider position in closed form.
    fn x_of(phi: f64) -> f64 {
        let s = M.r * phi.sin() - M.e;
        M.r * phi.cos() + (M.l * M.l - s * s).sqrt()
    }

    #[test]
    fn dead_centres_of_an_offset_slider_crank() {
        let turn = Sampled::sweep(&M, 0.0, TAU, 37, [3.0]).unwrap();
        let r = turn.range(X).unwrap();
        let [(a_out, outer), (a_in, inner)] = M.dead_centres();
        assert!((r.max.value - outer).abs() < 1e-12, "{} vs {outer}", r.max.value);
        assert!((r.min.value - inner).abs() < 1e-12);
        // Location: the analog's root; its error is the analog's error over the curvature.
        assert!((r.max.x - a_out).abs() < 1e-10, "{} vs {a_out}", r.max.x);
        assert!((r.min.x - a_in.rem_euclid(TAU)).abs() < 1e-10, "{} vs {a_in}", r.min.x);
        assert!(r.max.d1.abs() < 1e-12 && r.min.d1.abs() < 1e-12);
        let e = turn.extremes(X).unwrap();
        assert_eq!(e.len(), 2);
        assert_eq!(e[0].kind, Extreme::Max);
        // The offset makes the return stroke quicker than the working stroke.
        assert!((e[1].x() - e[0].x()) > PI);
    }

    #[test]
    fn states_between_samples_stay_on_the_branch_and_match_the_closed_form() {
        let turn = Sampled::sweep(&M, 0.0, TAU, 13, [3.0]).unwrap();
        for x in [0.1, 1.0, 2.9, 4.4, 6.2] {
            let k = turn.at(x).unwrap();
            assert!((k.q[0] - x_of(x)).abs() < 1e-12);
        }
        assert!(turn.at(7.0).is_err());
        // The input as a column: its value is the path parameter, its own analog 1.
        for j in turn.jets(SliderCrank::COL.phi).unwrap() {
            assert_eq!((j.value, j.d1, j.d2), (j.x, 1.0, 0.0));
        }
        assert!(Column::<SliderCrank>::named("nope").is_err());
        assert_eq!(Column::<SliderCrank>::named("h").unwrap(), SliderCrank::COL.h);
        assert_eq!(Column::<SliderCrank>::named("phi").unwrap().index(), ColumnIndex::Input(0));
        assert!(Sampled::sweep(&M, 1.0, 0.0, 10, [3.0]).is_err());
    }

    /// A sample count far beyond memory (given on a command line, say) is not reserved up
    /// front: the sweep starts, and its failure at the first solve (a guess that is not a
    /// number) is the error, rather than the process aborting on an allocation.
    #[test]
    fn a_huge_sample_count_is_not_reserved_up_front() {
        let r = Sampled::sweep(&M, 0.0, 1.0, 1 << 40, [f64::NAN]);
        assert!(r.is_err());
    }

    #[test]
    fn fourier_and_residual_of_the_slider_position() {
        let turn = Sampled::sweep(&M, 0.0, TAU, 129, [3.0]).unwrap();
        let f = turn.fourier(X, 8).unwrap();
        // Independent coefficients: trapezoidal sums of the closed form on a 4x finer grid.
        let n = 512;
        let xs: Vec<f64> = (0..n).map(|j| x_of(TAU * j as f64 / n as f64)).collect();
        let g = fourier::fourier(&xs, 0.0, TAU, 8).unwrap();
        assert!((f.a0 - g.a0).abs() < 1e-12);
        for k in 0..8 {
            assert!((f.a[k] - g.a[k]).abs() < 1e-12 && (f.b[k] - g.b[k]).abs() < 1e-12, "harmonic {}", k + 1);
        }
        // The residual after the first harmonic, against a dense scan of the closed form.
        let r = turn.unbalance(X, 1).unwrap();
        let c1 = |x: f64| g.eval_upto(1, x).0;
        let mut best = (0.0, 0.0f64);
        for i in 0..20_000 {
            let x = TAU * i as f64 / 20_000.0;
            let v = (x_of(x) - c1(x)).abs();
            if v > best.1 {
                best = (x, v);
            }
        }
        let (_, exact) = maximize(best.0 - 1e-3, best.0 + 1e-3, |x: f64| Ok((x_of(x) - c1(x)).abs())).unwrap();
        assert!((r.max_abs - exact).abs() < 1e-12, "{} vs {exact}", r.max_abs);
        // The unknown x returns to its value: periodic. Not so over half a turn.
        let half = Sampled::sweep(&M, 0.0, PI, 9, [3.0]).unwrap();
        assert!(half.fourier(X, 2).is_err());
    }

    #[test]
    fn peak_of_a_derived_quantity() {
        let turn = Sampled::sweep(&M, 0.0, TAU, 73, [3.0]).unwrap();
        // The largest acceleration analog of the slider, against a dense scan refined by Brent.
        let (x, v) = turn.peak(|k| k.d2q[0][0][0].abs()).unwrap();
        let acc = |phi: f64| M.kinematics_at_flat(&[phi], &[x_of(phi)], &Default::default()).unwrap().d2q[0][0][0];
        let mut best = (0.0, 0.0f64);
        for i in 0..7200 {
            let p = TAU * i as f64 / 7200.0;
            if acc(p).abs() > best.1 {
                best = (p, acc(p).abs());
            }
        }
        assert!((v - best.1).abs() < 1e-6 * best.1 && v >= best.1 - 1e-12, "{v} vs {}", best.1);
        assert!((x - best.0).abs() < 1e-3);
    }

    /// Ends whose difference overflows are sampled between them, the first at `from` (it was
    /// NaN, the others infinite).
    #[test]
    fn samples_between_ends_wider_than_f64_holds() {
        let s = Jet::sample(|x| Ok(Jet { x, ..Jet::default() }), -1e308, 1e308, 4).unwrap();
        let x: Vec<f64> = s.iter().map(|j| j.x).collect();
        assert_eq!(x, [-1e308, -0.5e308, 0.0, 0.5e308, 1e308]);
    }

    /// More jets than the memory kept at most (`MAX_COLLECTED_BYTES`, 1 GiB: 2^25 jets of 32
    /// bytes) are refused before `f` is called, with the most that fit, as a trace's points
    /// are: within [`MAX_SAMPLES`], 10^8 intervals reserved 3.2 GB, which the system may grant
    /// and then fail to give as the jets are written. The most that fit are sampled.
    #[test]
    fn more_jets_than_the_memory_budget_are_refused_before_sampling() {
        let fit = crate::paths::collected::MAX_COLLECTED_BYTES / size_of::<Jet>();
        let mut calls = 0usize;
        let r = Jet::sample(
            |x| {
                calls += 1;
                Ok(Jet { x, ..Jet::default() })
            },
            0.0,
            1.0,
            fit,
        );
        match r {
            Err(Error::InvalidArgument(m)) => assert!(m.contains(&format!("at most {}", fit - 1)), "{m}"),
            other => panic!("{:?}", other.map(|v| v.len())),
        }
        assert_eq!(calls, 0);
        assert!(fit <= MAX_SAMPLES);
    }

    /// A count of intervals beyond [`MAX_SAMPLES`] is refused before `f` is called once: the
    /// largest `usize` ran practically forever (and a large one collected jets no memory holds).
    #[test]
    fn absurd_interval_counts_are_refused_before_sampling() {
        for intervals in [MAX_SAMPLES + 1, usize::MAX / 64, usize::MAX] {
            let mut calls = 0usize;
            // Stops an unbounded run after a few calls with an error of its own.
            let r = Jet::sample(
                |x| {
                    calls += 1;
                    if calls > 1000 {
                        Err(Error::InvalidArgument("still sampling".into()))
                    } else {
                        Ok(Jet { x, ..Jet::default() })
                    }
                },
                0.0,
                1.0,
                intervals,
            );
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("at most")), "{intervals}: {r:?}");
            assert_eq!(calls, 0, "{intervals}");
        }
        assert_eq!(Jet::sample(|x| Ok(Jet { x, ..Jet::default() }), 0.0, 1.0, 1000).unwrap().len(), 1001);
    }

    /// Ends not finite are an error before `f` is called: `f` was handed NaN or infinite inputs
    /// (and a NaN end, sampled, gave NaN jets as `Ok`).
    #[test]
    fn ends_not_finite_are_refused_before_sampling() {
        for (from, to) in [(f64::NAN, 1.0), (0.0, f64::NAN), (f64::NEG_INFINITY, 1.0), (0.0, f64::INFINITY)] {
            let mut calls = 0;
            let r = Jet::sample(
                |x| {
                    calls += 1;
                    Ok(Jet { x, ..Jet::default() })
                },
                from,
                to,
                4,
            );
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("finite")), "{from} {to}: {r:?}");
            assert_eq!(calls, 0);
        }
    }

    /// A sweep of more samples than [`MAX_SAMPLES`] is refused at once: `Sampled` keeps every
    /// state, and the largest `usize` swept until memory ran out.
    #[test]
    fn absurd_sample_counts_of_a_sampled_sweep_are_refused() {
        for samples in [MAX_SAMPLES + 1, usize::MAX] {
            let r = Sampled::sweep(&M, 0.0, TAU, samples, [3.0]);
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("at most")), "{samples}: {:?}", r.err());
        }
    }

    /// A value not finite at a sample is an error, as in the search between samples: an
    /// infinite one was returned as the peak, a NaN with its sign bit set passed over.
    #[test]
    fn a_peak_of_values_not_finite_is_an_error() {
        let turn = Sampled::sweep(&M, 0.0, TAU, 73, [3.0]).unwrap();
        let at = turn.path_values()[20];
        for bad in [f64::INFINITY, -f64::NAN, f64::NAN] {
            let r = turn.peak(|k| if k.x[0] == at { bad } else { k.q[0] });
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("at the sample")), "{bad}: {r:?}");
        }
    }

    /// The example of the documentation above, run against the hand-written slider-crank.
    #[test]
    fn module_documentation_example() -> Result<(), crate::Error> {
        use crate::analysis::Sampled;
        use crate::analysis::demo::SliderCrank;
        use std::f64::consts::TAU;
        // `SliderCrank` stands for any mechanism declared with `kinloop::mechanism!` (here an offset
        // slider-crank written by hand: crank 1, rod 3, offset 0.5, one unknown `x`).
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
        let turn = Sampled::sweep(&m, 0.0, TAU, 73, [3.9])?; // every 5 degrees, one turn
        let x = turn.range(X)?; // dead centres, located exactly
        let outer = (4.0f64.powi(2) - 0.25).sqrt(); // crank and rod stretched
        let inner = (2.0f64.powi(2) - 0.25).sqrt(); // crank and rod folded
        assert!((x.max.value - outer).abs() < 1e-12 && (x.min.value - inner).abs() < 1e-12);
        assert!((x.max.x - 0.5f64.atan2(outer)).abs() < 1e-10);
        assert!((x.span() - (outer - inner)).abs() < 1e-12); // the stroke
        let harmonics = turn.fourier(X, 4)?; // x = a0 + a1 cos phi + ...
        assert!((harmonics.a[0] - 1.0).abs() < 1e-12); // the crank's own cos phi
        Ok(())
    }

    /// The example of the documentation above, run against the hand-written slider-crank.
    #[test]
    fn sampled_documentation_example() -> Result<(), crate::Error> {
        use crate::analysis::demo::SliderCrank;
        use crate::analysis::{Extreme, Sampled};
        use std::f64::consts::TAU;
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.0 }; // a centred slider-crank
        let turn = Sampled::sweep(&m, 0.0, TAU, 37, [4.0])?;
        // Dead centres at 0 and 180 degrees (the first at the start of the range is not interior).
        let e = turn.extremes(X)?;
        assert_eq!(e.len(), 1);
        assert_eq!(e[0].kind, Extreme::Min);
        assert!((e[0].x() - TAU / 2.0).abs() < 1e-10 && (e[0].value() - 2.0).abs() < 1e-12);
        // The largest acceleration analog |x''| = r + r^2/l at the outer dead centre.
        let (at, peak) = turn.peak_of(SliderCrank::COL.x, |j| j.d2.abs())?;
        assert!((peak - (1.0 + 1.0 / 3.0)).abs() < 1e-12 && at.cos() > 1.0 - 1e-12);
        // After the first harmonic, what remains is mostly the second, about r^2 / (4 l) cos 2 phi.
        let r = turn.unbalance(X, 1)?;
        assert!((r.max_abs - 1.0 / 12.0).abs() < 5e-3);
        // Any state of the range, on the sweep's branch.
        assert!((turn.at(1.0)?.q[0] - (1f64.cos() + (9.0 - 1f64.sin().powi(2)).sqrt())).abs() < 1e-12);
        Ok(())
    }

    /// A turn that starts (and so ends) at the outer dead centre: the analog there rounds to a
    /// tiny non-zero value, and that end used to be reported as an extreme, twice.
    #[test]
    fn a_range_starting_at_a_dead_centre_reports_only_interior_extremes() {
        let m = SliderCrank { r: 1.0, l: 3.0, e: 0.5 };
        let outer = (4.0f64.powi(2) - 0.25).sqrt();
        let start = 0.5f64.atan2(outer);
        let turn = Sampled::sweep(&m, start, start + std::f64::consts::TAU, 37, [outer]).unwrap();
        let e = turn.extremes(X).unwrap();
        assert_eq!(e.len(), 1, "{e:?}");
        assert_eq!(e[0].kind, Extreme::Min);
        // The inner dead centre: crank and rod folded, x = sqrt((l - r)^2 - e^2).
        assert!((e[0].value() - (4.0f64 - 0.25).sqrt()).abs() < 1e-12, "{e:?}");
    }
}
