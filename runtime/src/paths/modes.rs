//! Assembly modes: the distinct solutions of the position equations at one input, over any
//! [`Kernel`] ([`assembly_modes_of`]).

use crate::dims::{Dims, JacState, KinState};
use crate::error::Error;
use crate::kin::Kin;
use crate::kinds::QuantityKind;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::{Compiled, Kernel, KinOf, Q, X, check_sizes};
use crate::paths::curve::sane;
use crate::solvers::newton::NewtonConfig;
use crate::solvers::turns::unwrap_to_turn;
use std::f64::consts::PI;

/// Distance between two angles, treating differences of whole turns as equal (an angle and the
/// same angle plus 2 pi are one configuration).
fn turn_distance(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(2.0 * PI);
    d.min(2.0 * PI - d)
}

/// Finds the distinct assembly modes at input `x` by multi-start Newton: the declared guess,
/// then `starts` deterministic quasi-random starts spread around it, an angle over a full turn,
/// another unknown (a length) over as many of its units (the size of the loops it closes, at
/// the guess) (and the guess with every unknown negated, which reaches mirrored slider
/// solutions).
///
/// Two solutions are the same mode when their block determinant signs agree, every angle
/// agrees modulo whole turns and every other unknown within `1e-7` of its unit (relative to its
/// value where that is larger): the same modes whatever the unit of length. Each mode's angles
/// are given on the declared guess's turn (within half a turn of its values). Modes are sorted by their determinant signs, so the order is
/// stable. Pick one with a readable rule on the named state, e.g.
/// `modes.into_iter().find(|s| s.out.c.y > 0.0)` ("elbow up").
///
/// Empty where no start solves (the links cannot close at `x`: no mode). Errors, not an empty
/// list: an input or a parameter NaN or infinite ([`Error::NonFinite`], which every start
/// would meet), an invalid `cfg` or more `starts` than
/// [`MAX_SAMPLES`](crate::analysis::MAX_SAMPLES) ([`Error::InvalidArgument`]),
/// [`Error::Singular`] where the only positions found are singular (`x` at a limit position,
/// where two modes meet: the links close there, but in no mode a sweep can leave), and
/// [`Error::NoConvergence`] (the first start's that ran out of iterations) where no start
/// solves and some ran out of `cfg.max_iterations`: the search cannot then tell links that
/// close nowhere (which fail as [`Error::NoAssembly`]) from a configuration too tight to solve
/// (a `max_iterations` of 0 to 2 fails every start of a four-bar that assembles).
///
/// A compiled mechanism's [`assembly_modes_of`] (through [`Compiled`]).
pub fn assembly_modes<M, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    x: &[f64; NI],
    starts: usize,
    cfg: &NewtonConfig,
) -> Result<Vec<Kin<N, NI, NO>>, Error>
where
    M: Mechanism<N, NI, NO>,
{
    // `assembly_modes_of` refuses an angle parameter too large to resolve.
    assembly_modes_of(&Compiled(m), x, starts, cfg)
}

/// [`assembly_modes`] over any [`Kernel`]: a compiled mechanism's, or one whose sizes are known
/// at run time (`kinloop_model::Model::assembly_modes`). The errors of [`assembly_modes`] (an
/// angle parameter beyond the `largest_precise_angle` of `cfg` among them:
/// [`Kernel::check_param_angles`]), and
/// [`Error::InvalidArgument`] for an `x` of another size than the kernel's inputs.
pub fn assembly_modes_of<K: Kernel>(
    m: &K,
    x: &X<K>,
    starts: usize,
    cfg: &NewtonConfig,
) -> Result<Vec<KinOf<K>>, Error> {
    check_sizes(m, "assembly_modes", &[x], &[])?;
    cfg.validate()?;
    m.check_param_angles(cfg)?;
    // The starts are solved one after another: a count no analysis takes would run for hours.
    crate::analysis::check_sample_count("starts", starts).map_err(Error::InvalidArgument)?;
    let n = m.dims().n();
    let g0 = m.guess(x);
    // Each unknown's unit: a radian for an angle; for another (a length) its generated unit at
    // the guess, the size of the loops it closes (one where that is not positive and finite).
    // The starts' spread and the test of two modes being one are measured in it: in absolute
    // terms a mechanism of lengths 1e-9 had its four modes taken for two (every length within
    // 1e-7 of the others), and lengths differing by whole multiples of 2 pi for one.
    let jac = m.jacobian(x, &g0);
    let angle: Vec<bool> = (0..n).map(|u| m.unknown_kind(u) == QuantityKind::Angle).collect();
    let unit: Vec<f64> = (0..n).map(|u| if angle[u] { 1.0 } else { sane(jac.unit(u)) }).collect();
    let same_value = |u: usize, a: f64, b: f64| {
        let d = if angle[u] { turn_distance(a, b) } else { (a - b).abs() };
        d < 1e-7 * (unit[u] + b.abs())
    };
    let mut found: Vec<KinOf<K>> = Vec::new();
    // A mode's angles on the turn of the declared guess's (the nearest to it): a start a turn
    // away solves the same mode a turn away, and the modes of a list should compare by their
    // values. Solved again there (the closed forms put an angle on its guess's turn), so that
    // every value of the state is the solve's own; the state as found if that fails.
    let on_guess_turn = |k: KinOf<K>| -> KinOf<K> {
        let mut q = g0.clone();
        q.as_mut().copy_from_slice(k.q());
        let mut moved = false;
        for (u, v) in q.as_mut().iter_mut().enumerate() {
            if m.unknown_kind(u) == QuantityKind::Angle {
                let on_turn = unwrap_to_turn(*v, g0.as_ref()[u]);
                moved |= on_turn != *v;
                *v = on_turn;
            }
        }
        match moved.then(|| m.kinematics(x, &q, cfg)) {
            Some(Ok(on_turn)) if on_turn.health().det_signs == k.health().det_signs => on_turn,
            _ => k,
        }
    };
    // The first singular position a start reached: the answer where no start finds a mode.
    let mut singular: Option<Error> = None;
    // The first start that ran out of iterations: otherwise the answer where none finds a mode.
    let mut undecided: Option<Error> = None;
    let mut try_start = |g: &Q<K>, found: &mut Vec<KinOf<K>>| -> Result<(), Error> {
        match m.kinematics(x, g, cfg) {
            Ok(k) => {
                let same = found.iter().any(|f| {
                    f.health().det_signs == k.health().det_signs && (0..n).all(|u| same_value(u, f.q()[u], k.q()[u]))
                });
                if !same {
                    found.push(on_guess_turn(k));
                }
                Ok(())
            }
            // A value not finite (an input, a parameter, or the declared guess they give) fails
            // every start alike: the list would be empty as where the links cannot close.
            Err(e @ Error::NonFinite { .. }) => Err(e),
            Err(e @ Error::Singular { .. }) => {
                singular.get_or_insert(e);
                Ok(())
            }
            Err(e @ Error::NoConvergence { .. }) => {
                undecided.get_or_insert(e);
                Ok(())
            }
            Err(_) => Ok(()),
        }
    };
    try_start(&g0, &mut found)?;
    let mut neg = g0.clone();
    for v in neg.as_mut() {
        *v = -*v;
    }
    try_start(&neg, &mut found)?;
    // Additive recurrence with irrational steps per unknown (a Kronecker sequence).
    let alpha: [f64; 8] = [
        0.618_033_988_749_895,
        0.414_213_562_373_095,
        0.732_050_807_568_877,
        0.236_067_977_499_79,
        0.645_751_311_064_591,
        0.316_624_790_355_4,
        0.605_551_275_463_989,
        0.123_105_625_617_661,
    ];
    let mut g = g0.clone();
    for k in 1..=starts {
        g.as_mut().copy_from_slice(g0.as_ref());
        for (u, v) in g.as_mut().iter_mut().enumerate() {
            let a = alpha[u % 8] + 0.01 * (u / 8) as f64;
            let frac = (k as f64 * a).fract();
            *v += (2.0 * frac - 1.0) * PI * (unit[u] + 0.25 * v.abs());
        }
        try_start(&g, &mut found)?;
    }
    if found.is_empty()
        && let Some(e) = singular.or(undecided)
    {
        return Err(e);
    }
    found.sort_by(|a, b| a.health().det_signs.cmp(&b.health().det_signs).then(a.q()[0].total_cmp(&b.q()[0])));
    Ok(found)
}
