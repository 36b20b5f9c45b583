//! Where a mechanism assembles, for a designer whose mechanism "cannot be assembled" at the
//! input asked for: nearest an input angle of a one-input mechanism ([`assembly_near_of`],
//! answering with [`Assembly`]), or first along a straight path of any inputs
//! ([`assembly_along_of`], answering with [`PathEntry`]).

use super::curve::Path;
use super::reach::{Reach, reachable_of};
use crate::dims::{Dims, KinState};
use crate::error::Error;
use crate::kinds::QuantityKind;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::{Compiled, Kernel, Q, X, check_inputs_finite, check_sizes};
use crate::number::Count;
use crate::solvers::newton::NewtonConfig;
use std::f64::consts::TAU;

/// The angles of the turn about the input asked for at which [`assembly_near`] tries a point
/// solve: one a degree. A stretch of assembly narrower than that can be missed (a mechanism
/// within a degree of not assembling at all), which the answer's wording allows for.
pub const ASSEMBLY_SAMPLES: usize = 360;

/// Where a mechanism assembles nearest the input asked for ([`assembly_near`]): the sample
/// nearest it at which a point solve from the declared guess succeeds, and the stretch of the
/// input reachable from there on that solve's assembly mode, a turn each way at most.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Assembly<X> {
    /// The sample nearest the input asked for at which the point solve from the declared guess
    /// succeeds (the input asked for itself, where it does).
    pub found: X,
    /// The stretch reachable from `found` on its assembly mode: its ends are limit positions
    /// (with their events) or, where no limit position comes within a turn, the search's ends,
    /// a turn from `found` (a crank that turns fully on this mode).
    pub reach: Reach<X>,
}

impl<X> Assembly<X> {
    /// Whether the input turns fully on this assembly mode: neither end of the stretch is a
    /// limit position within a turn of where it was found.
    pub fn turns_fully(&self) -> bool {
        self.reach.from_event.is_none() && self.reach.to_event.is_none()
    }

    /// The same answer with the inputs converted (e.g. to named inputs).
    pub fn map_inputs<Y>(self, mut f: impl FnMut(X) -> Y) -> Assembly<Y> {
        Assembly { found: f(self.found), reach: self.reach.map_inputs(f) }
    }
}

/// Where a mechanism of one angle input assembles nearest the input `at` (where a point solve
/// failed with [`Error::NoAssembly`], say): point solves from the declared guess
/// ([`Mechanism::guess_flat`] at each angle) at `at`, then at `samples` angles of the turn about it,
/// spread evenly and tried nearest first, of two as near (one each way) the greater first; from
/// the first that solves, the stretch reachable on its assembly mode
/// ([`reachable`](super::reach::reachable), a turn each way). So where the mechanism assembles as
/// near `at` on both sides, `found` is the sample above it (counter-clockwise). `None` where no
/// sample solves: the loops close nowhere on the turn from the declared guess, within the
/// samples' spacing (a stretch narrower than that, or one that only another guess reaches,
/// goes unseen). A compiled mechanism's [`assembly_near_of`] (through [`Compiled`]).
///
/// A sample is passed over where its solve fails with [`Error::NoAssembly`] or
/// [`Error::Singular`] (a limit position met to the rounding, from which no sweep leaves): the
/// mechanism does not assemble there. So is one where a sweep cannot start from the position
/// solved ([`Error::NearSingular`], [`Error::SingularStart`]: nearer a singular position than a
/// sweep accepts, it assembles, but a hair inside a limit position, a sample from one that is a
/// start).
///
/// A solve that runs out of iterations ([`Error::NoConvergence`]: Newton's method from the
/// declared guess, far from the position) decides nothing: the mechanism may assemble there.
/// Where one of the samples tried before the first that is a start (`at` itself, or one as
/// near or nearer) ran out of iterations, the search cannot tell whether that nearer sample
/// assembles, and a farther one would be no answer to "nearest": the answer is then the first
/// such [`Error::NoConvergence`], naming the iterations and the input, not the farther sample.
/// A four-bar that assembles at every input, its Newton solves allowed 4 iterations, solves
/// from the declared guess only between 20 and 113 degrees: asked about 0, it answered 20
/// degrees. So, too, where no sample is a start and some solve ran out of iterations (a
/// `max_iterations` of 0 to 2 fails every solve of that four-bar): not `None`. Links that close
/// nowhere fail as [`Error::NoAssembly`] (a closed form's test, or Newton's stalled residual),
/// and stay `None`. Raise `max_iterations` (or declare a guess nearer the positions) where the
/// answer is `NoConvergence`.
///
/// Errors: a mechanism of other than one input, or whose input is not an angle, fewer than 2
/// or more than [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES) samples, an input so large that
/// the samples' spacing rounds away ([`Error::InvalidArgument`]); `at` not finite
/// ([`Error::NonFinite`]); [`Error::NoConvergence`] where a sample tried before the answer's, or
/// before none, ran out of iterations (above); any other error of a point solve (a declared
/// expression that leaves its domain) or of the sweeps.
pub fn assembly_near<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    at: [f64; NI],
    samples: usize,
) -> Result<Option<Assembly<[f64; NI]>>, Error>
where
    M: Mechanism<N, NI, NO>,
{
    assembly_near_of(&Compiled(m), at, samples)
}

/// [`assembly_near`] over any [`Kernel`] (a compiled mechanism's, or one whose sizes are known
/// at run time: `kinloop_model::Model::assembly_near`), with the kernel's configuration
/// ([`Kernel::solver_config`]); `at` of the kernel's size (a mismatch is an
/// `Error::InvalidArgument`).
pub fn assembly_near_of<K: Kernel>(m: &K, at: X<K>, samples: usize) -> Result<Option<Assembly<X<K>>>, Error> {
    check_sizes(m, "assembly_near", &[&at], &[])?;
    let d = m.dims();
    if d.ni() != 1 || m.input_kind(0) != QuantityKind::Angle {
        let has = match d.ni() {
            1 => format!("its input `{}` is not an angle", m.input_name(0)),
            n => format!("it has {n} inputs"),
        };
        return Err(Error::InvalidArgument(format!(
            "assembly_near: `{}`: {has}, and the search samples the turn of a single input angle",
            m.name()
        )));
    }
    if samples < 2 {
        return Err(Error::InvalidArgument(format!(
            "assembly_near: {} asked for: the turn needs at least 2",
            Count(samples, "sample")
        )));
    }
    crate::analysis::check_sample_count("samples of `assembly_near`", samples).map_err(Error::InvalidArgument)?;
    check_inputs_finite(m, &at)?;
    let cfg = m.solver_config();
    m.check_param_angles(&cfg.newton)?;
    let spacing = TAU / samples as f64;
    let x0 = at[0];
    // Beyond this the samples would not be apart (a turn's doubles too coarse): no search.
    if x0 + spacing == x0 || x0 - spacing == x0 {
        return Err(Error::InvalidArgument(format!(
            "assembly_near: {x0} rad is too large for the turn about it to be sampled every {spacing} rad"
        )));
    }
    let input = |x: f64| {
        let mut v = at.clone();
        v[0] = x;
        v
    };
    // Nearest first: `at`, then one spacing each way, two, ... up to half a turn each way; the
    // side above `at` first, the documented tie-break between two samples as near.
    let offsets = std::iter::once(0.0).chain((1..=samples / 2).flat_map(|j| [j as f64, -(j as f64)]));
    let mut undecided = None;
    for j in offsets {
        let x = input(x0 + j * spacing);
        let Some(q) = solved(m, &x, &cfg.newton, &mut undecided)? else { continue };
        // A sample tried before this one, as near or nearer, may assemble: no answer.
        if let Some(e) = undecided.take() {
            return Err(e);
        }
        // A turn each way: a linkage's stretch between two limit positions is shorter than that,
        // and one that reaches both ends turns fully.
        match reachable_of(m, x.clone(), input(TAU), q, samples / 2 + 1) {
            Ok(reach) => return Ok(Some(Assembly { found: x, reach })),
            // Solved, but nearer a singular position than a sweep starts from (within a hair of
            // a limit position): the next sample is a start.
            Err(Error::SingularStart { .. } | Error::NearSingular { .. }) => {}
            Err(e) => return Err(e),
        }
    }
    nowhere(undecided)
}

/// The positions at `x` solved from the declared guess, or `None` where the solve fails with
/// [`Error::NoAssembly`] or [`Error::Singular`] (the mechanism does not assemble there) or with
/// [`Error::NoConvergence`] (undecided: the first is kept in `undecided`, which the searches
/// answer with where it leaves their answer in doubt, see [`nowhere`]); any other error is
/// returned.
fn solved<K: Kernel>(
    m: &K,
    x: &X<K>,
    cfg: &NewtonConfig,
    undecided: &mut Option<Error>,
) -> Result<Option<Q<K>>, Error> {
    let mut q = m.guess(x);
    match m.kinematics(x, &q, cfg) {
        Ok(k) => {
            q.as_mut().copy_from_slice(k.q());
            Ok(Some(q))
        }
        Err(e @ Error::NoConvergence { .. }) => {
            undecided.get_or_insert(e);
            Ok(None)
        }
        Err(Error::NoAssembly { .. } | Error::Singular { .. }) => Ok(None),
        Err(e) => Err(e),
    }
}

/// A search's answer where no sample was found: `None` (the mechanism assembles nowhere it
/// looked), unless a solve ran out of iterations (`undecided`, its [`Error::NoConvergence`]):
/// then the search cannot tell "nowhere" from a solver configured too tightly to find it, and
/// says so with that error rather than answer "nowhere".
fn nowhere<T>(undecided: Option<Error>) -> Result<Option<T>, Error> {
    match undecided {
        Some(e) => Err(e),
        None => Ok(None),
    }
}

/// The most halvings of the stretch between two samples where [`assembly_along`] locates the
/// path's entry: the fraction's 53 bits and then some.
const BISECTIONS: usize = 64;

/// Where a mechanism first assembles along the straight path from `from` to `to`
/// ([`assembly_along`]): the fraction of the path where point solves from the declared guess
/// begin to succeed, located between two samples, the inputs there, and the first sample that
/// solves, from which a sweep can start.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct PathEntry<X> {
    /// The fraction of the path (0 at `from`, 1 at `to`) where the point solves begin to
    /// succeed: the first solvable input found by bisection between the last sample that fails
    /// and the first that solves, to the rounding of the fraction. Usually a limit position, a
    /// hair inside it, from which a sweep may not start (too near a singular position).
    pub fraction: f64,
    /// The inputs at `fraction`.
    pub at: X,
    /// The first sample along the path that solves (`from` itself where it does), a start for a
    /// sweep along the rest of the path.
    pub sample: X,
}

/// Where a mechanism of any number of inputs first assembles along the straight path from
/// `from` to `to`: point solves from the declared guess ([`Mechanism::guess_flat`] at each
/// input) at `from` and then at `samples` equally spaced inputs after it up to `to`; between the
/// last that fails and the first that solves, the fraction where they begin to succeed by
/// bisection. `None` where no sample solves (the path stays outside the assembly within the
/// samples' spacing). A compiled mechanism's [`assembly_along_of`] (through [`Compiled`]).
///
/// A sample counts as not assembling where its solve fails with [`Error::NoAssembly`] or
/// [`Error::Singular`]; any other error but [`Error::NoConvergence`] is returned. A solve that
/// runs out of iterations decides nothing (the mechanism may assemble there), as for
/// [`assembly_near`]: where a sample before the first that solves ran out of iterations, the
/// path may enter the assembly there, and the answer is that [`Error::NoConvergence`], not an
/// entry after it; so, too, where no sample solves and some ran out of iterations, not `None`.
/// Between the last sample that fails and the first that solves, a point whose solve runs out
/// of iterations counts as failing: the bisection goes on above it, so that `fraction` is a
/// point that solves, within the samples' spacing of where the solves begin.
///
/// Errors: fewer than 1 or more than [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES) samples,
/// `from` equal to `to`, ends so far apart that `to - from` overflows
/// ([`Error::InvalidArgument`]); an input not finite ([`Error::NonFinite`]);
/// [`Error::NoConvergence`] where a sample before the first that solves, or before none, ran
/// out of iterations (above); any other error of a point solve.
pub fn assembly_along<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    from: [f64; NI],
    to: [f64; NI],
    samples: usize,
) -> Result<Option<PathEntry<[f64; NI]>>, Error>
where
    M: Mechanism<N, NI, NO>,
{
    assembly_along_of(&Compiled(m), from, to, samples)
}

/// [`assembly_along`] over any [`Kernel`], with the kernel's configuration
/// ([`Kernel::solver_config`]); `from` and `to` of the kernel's size (a mismatch is an
/// `Error::InvalidArgument`).
pub fn assembly_along_of<K: Kernel>(
    m: &K,
    from: X<K>,
    to: X<K>,
    samples: usize,
) -> Result<Option<PathEntry<X<K>>>, Error> {
    check_sizes(m, "assembly_along", &[&from, &to], &[])?;
    if samples < 1 {
        return Err(Error::InvalidArgument("assembly_along: 0 samples asked for: at least `to` is one".into()));
    }
    crate::analysis::check_sample_count("samples of `assembly_along`", samples).map_err(Error::InvalidArgument)?;
    check_inputs_finite(m, &from)?;
    check_inputs_finite(m, &to)?;
    if from.as_ref() == to.as_ref() {
        return Err(Error::InvalidArgument("assembly_along: `from` equals `to`: the path is empty".into()));
    }
    let cfg = m.solver_config();
    m.check_param_angles(&cfg.newton)?;
    let path = Path::new(from, to);
    // Both ends finite, `to - from` can still overflow (`1e308 - -1e308`): every input on the
    // path would be infinite or NaN (`from + 0 * inf`), an error about a NaN nobody gave.
    if !path.len.is_finite() {
        return Err(Error::InvalidArgument(
            "assembly_along: `to - from` overflows (beyond the largest double): give nearer ends of the path".into(),
        ));
    }
    let solves = |tau: f64, undecided: &mut Option<Error>| {
        Ok::<_, Error>(solved(m, &path.at_tau(tau), &cfg.newton, undecided)?.is_some())
    };
    let mut undecided = None;
    let mut before = 0.0;
    for k in 0..=samples {
        let tau = k as f64 / samples as f64;
        if !solves(tau, &mut undecided)? {
            before = tau;
            continue;
        }
        // A sample before this one may assemble: no entry here is the path's first.
        if let Some(e) = undecided.take() {
            return Err(e);
        }
        // Between the last sample that fails and this one: where the solves begin.
        let (mut lo, mut hi) = (before, tau);
        if k > 0 {
            // Until the fractions or their inputs are neighbours (a start at a limit position
            // would otherwise halve towards 0 through the subnormals).
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi || path.at_tau(lo).as_ref() == path.at_tau(hi).as_ref() {
                    break;
                }
                // Between the samples a solve that runs out of iterations counts as failing (see
                // `assembly_along`): `hi` stays a point that solves.
                if solves(mid, &mut None)? { hi = mid } else { lo = mid }
            }
        }
        return Ok(Some(PathEntry { fraction: hi, at: path.at_tau(hi), sample: path.at_tau(tau) }));
    }
    nowhere(undecided)
}
