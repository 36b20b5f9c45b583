//! The assembly mode of a closed-form block solved by Newton beyond the closed forms' sizes: the
//! root its closed form picks from the guess at size 1 (the sign of the block's Jacobian
//! determinant there), taken where Newton reached the other (`keep_modes`), the other root
//! found from the block's residuals alone (`mirror`), in the equations' own magnitudes.

use super::system::{Block, System, blank_evaluation, scaled_residual};
use crate::solvers::newton::{BlockEval, BlockFailure, Magnitudes, Solved, newton};
use crate::solvers::turns::unwrap_to_turn;
use core::f64::consts::PI;

/// The sign of the determinant of `block`'s diagonal block of the Jacobian in `ev` (0 where it
/// is zero or not a number): each row divided by its largest entry first, so that the products
/// of lengths about `1e±200` neither overflow nor underflow (a positive factor keeps the sign).
fn det_sign<const N: usize>(ev: &BlockEval<N, 0>, block: &Block) -> f64 {
    let row = |r: usize| {
        let v: [f64; 2] = core::array::from_fn(|i| block.cols.get(i).map_or(0.0, |&u| ev.j[r][u]));
        let m = v[0].abs().max(v[1].abs());
        if m > 0.0 { v.map(|x| x / m) } else { v }
    };
    let det = match block.rows[..] {
        [r] => row(r)[0],
        [r0, r1] => {
            let (a, b) = (row(r0), row(r1));
            a[0] * b[1] - a[1] * b[0]
        }
        _ => 0.0,
    };
    if det > 0.0 {
        1.0
    } else if det < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// [`whole_position`](super::whole_position)'s `solved` with each closed-form block of `blocks` (in
/// solve order) in the assembly mode its closed form picks from the guess `z0` at size 1. A closed
/// form's root is the one whose block Jacobian's determinant has the sign it has at the guess (the
/// blocks before it solved): for `a cos q + b sin q = c` the root where `h' = b cos q - a sin q`
/// has the sign of `h'` at the guess, for a dyad the one whose links' cross product has the sign of
/// the guess's, for a length `s` along a turning direction `w(q)` (`s w(q) + e = 0`) the one whose
/// length has the guess's sign (the determinant is `s` times `w × w'`, of one sign), and for an
/// angle and a slider (`m (cos q, sin q) + d s + e = 0`) the root of the slider-free combination
/// `d1 row0 - d0 row1`, an angle equation whose `h'` is the determinant
/// (`codegen/src/emit/closed_form.rs`); the determinant vanishes only at a limit position, where
/// the two modes meet. Newton goes wherever it converges: a four-bar driven by its rocker, from its
/// declared guess, reached the other mode at about half its inputs. So where a block's sign differs
/// from the guess's, its other root is taken (the mirror image, found from the block's residuals
/// alone: [`mirror`]) and Newton solved again from there: the blocks up to it are at their roots,
/// and the whole Jacobian is block-triangular, so its steps solve the blocks after it and leave
/// those. Where a sign is zero (a limit position), nothing changes.
#[cold]
#[inline(never)]
pub(super) fn keep_modes<const N: usize>(
    mut solved: Solved<N>,
    z0: &[f64; N],
    system: &System<'_, N>,
    blocks: &[Block],
    mags: &Magnitudes<N>,
    eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Result<Solved<N>, BlockFailure> {
    let mut ev = blank_evaluation::<N>();
    for block in blocks.iter().filter(|b| b.closed_form) {
        let z = solved.z;
        let mut at_guess = z;
        for &u in &block.cols {
            at_guess[u] = z0[u];
        }
        eval(&at_guess, &mut ev);
        let want = det_sign(&ev, block);
        eval(&z, &mut ev);
        let have = det_sign(&ev, block);
        solved.evaluations += 2;
        if want == 0.0 || have == 0.0 || want == have {
            continue;
        }
        // `mirror`'s evaluations and the one at its image below, counted as they are made.
        let mut counted = |z: &[f64; N], ev: &mut BlockEval<N, 0>| {
            solved.evaluations += 1;
            eval(z, ev);
        };
        let mirrored = mirror(&z, z0, system, block, &mut counted);
        let Some(mirrored) = mirrored else { continue };
        counted(&mirrored, &mut ev);
        // The whole system solved already (the block the last, or those after it unmoved): the
        // mirror image itself. Newton's last correction, applied even at a root, is about the
        // rounding of the residual over the determinant, which near a limit position is
        // `1e-7` rad where the two modes are closer than that (measured on the four-bar driven
        // by its rocker at its limit: its coupler moved by `6e-7` rad).
        let rho = scaled_residual(&ev.f, &system.scale);
        if rho <= system.cfg.residual_tol {
            solved = Solved { z: mirrored, residual: rho, ..solved };
            continue;
        }
        let again = newton(mirrored, &mut ev, system.cfg, &mut *eval, mags)?;
        solved = Solved {
            iterations: solved.iterations + again.iterations,
            evaluations: solved.evaluations + again.evaluations,
            ..again
        };
    }
    Ok(solved)
}

/// The other root of `block` at `z` (a root of `system`, in its units), with its angles on the
/// turns of the guess `z0`, the other unknowns as they are: `None` where it is not finite. Every
/// closed form is linear in the sines and cosines of its angles, so the residuals at `z` and with
/// an angle half a turn on give the block's terms without knowing its coefficients, in the
/// equations' own magnitudes (no products of lengths, which leave `f64` at these sizes). One angle,
/// `f(q) = A cos q + B sin q - C`: with `P = (f(q) - f(q + π)) / 2 = A cos q + B sin q` and `Q =
/// f'(q) = B cos q - A sin q`, `atan2(Q, P)` is the turn from `q` to the axis `atan2(B, A)` the two
/// roots are symmetric about, so the other root is `q + 2 atan2(Q, P)`. A dyad, `F = E + w0(q0) +
/// w1(q1)` with `w_i` a link turning with its angle (`w_i = (F(q) - F(q_i + π)) / 2`, turning one
/// way or the other, `ε_i` the sign of `w_i × dw_i/dq_i`): the other root is the mirror image
/// across the line of `E`, each `w_i` reflected, each angle turned by `2 ε_i (angle(E) -
/// angle(w_i))`. An angle `q` with a length `s`: along a turning direction (`s w(q) + e = 0`, `w(q
/// + π) = -w(q)`) the other root is `(q + π, -s)`, which its residuals (to the system's tolerance)
/// tell; with a slider of fixed direction `d` (`m (cos q, sin q) + d s + e = 0`) the angle's other
/// root is the one angle equation's of `d1 F0 - d0 F1` (`d` the slider's Jacobian column, rows
/// normalised as in [`det_sign`]), its length left to Newton's solve from there.
fn mirror<const N: usize>(
    z: &[f64; N],
    z0: &[f64; N],
    system: &System<'_, N>,
    block: &Block,
    eval: &mut impl FnMut(&[f64; N], &mut BlockEval<N, 0>),
) -> Option<[f64; N]> {
    let &System { scale, unit, turns, cfg, .. } = system;
    let mut ev = blank_evaluation::<N>();
    eval(z, &mut ev);
    let (f, j) = (ev.f, ev.j);
    // The residuals with angle `u` half a turn on and, where `negated` names one, that unknown
    // negated.
    let mut turned = |u: usize, negated: Option<usize>, ev: &mut BlockEval<N, 0>| {
        let mut half = *z;
        half[u] += PI / unit[u];
        if let Some(s) = negated {
            half[s] = -z[s];
        }
        eval(&half, ev);
        ev.f
    };
    // The block's terms that turn with angle `u`: half the difference of the residuals at `z`
    // and with `u` half a turn on (halved first, so that nothing overflows).
    let halves = |g: [f64; N]| {
        let half_difference = |r: usize| f[r] / 2.0 - g[r] / 2.0;
        [half_difference(block.rows[0]), block.rows.get(1).map_or(0.0, |&r| half_difference(r))]
    };
    // The turn from angle `u` to the other root of the angle equation `g`, given `g`'s turning
    // terms `p` and its derivative `dg` (by `z[u]`).
    let other_angle = |u: usize, p: f64, dg: f64| z[u] + 2.0 * (dg / unit[u]).atan2(p) / unit[u];
    let mut out = *z;
    match (&block.rows[..], &block.cols[..]) {
        (&[r], &[u]) => {
            let p = halves(turned(u, None, &mut ev))[0];
            out[u] = other_angle(u, p, j[r][u]);
        }
        (&[r0, r1], &[u0, u1]) if turns[u0] && turns[u1] => {
            let w = [halves(turned(u0, None, &mut ev)), halves(turned(u1, None, &mut ev))];
            let e = [f[r0] - w[0][0] - w[1][0], f[r1] - w[0][1] - w[1][1]];
            let to_e = e[1].atan2(e[0]);
            for (i, &u) in [u0, u1].iter().enumerate() {
                // The sign of `w × dw/dq` from the row-normalised values (see `det_sign`).
                let m = w[i][0].abs().max(w[i][1].abs());
                let d = [j[r0][u], j[r1][u]];
                let n = d[0].abs().max(d[1].abs());
                if !(m > 0.0 && n > 0.0) {
                    return None;
                }
                let cross = (w[i][0] / m) * (d[1] / n) - (w[i][1] / m) * (d[0] / n);
                let eps = if cross > 0.0 { 1.0 } else { -1.0 };
                out[u] = z[u] + eps * 2.0 * (to_e - w[i][1].atan2(w[i][0])) / unit[u];
            }
        }
        (&[r0, r1], &[c0, c1]) if turns[c0] != turns[c1] => {
            let (u, s) = if turns[c0] { (c0, c1) } else { (c1, c0) };
            let g = turned(u, Some(s), &mut ev);
            if g[r0].abs() / scale[r0] <= cfg.residual_tol && g[r1].abs() / scale[r1] <= cfg.residual_tol {
                out[u] = z[u] + PI / unit[u];
                out[s] = -z[s];
            } else {
                let n = j[r0][s].abs().max(j[r1][s].abs());
                if n.is_nan() || n == 0.0 {
                    return None;
                }
                let d = [j[r0][s] / n, j[r1][s] / n];
                let w = halves(turned(u, None, &mut ev));
                out[u] = other_angle(u, d[1] * w[0] - d[0] * w[1], d[1] * j[r0][u] - d[0] * j[r1][u]);
            }
        }
        _ => return None,
    }
    for &u in block.cols.iter().filter(|&&u| turns[u]) {
        out[u] = unwrap_to_turn(out[u] * unit[u], z0[u] * unit[u]) / unit[u];
    }
    out.iter().all(|v| v.is_finite()).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::super::{AtLimit, whole_position};
    use super::*;
    use crate::solvers::newton::NewtonConfig;

    /// `2 cos q + sin q = 1` times `1e200` (terms whose squares leave `f64`): roots `π/2` (where
    /// `h' = cos q - 2 sin q < 0`) and `-atan(3/4)` (`h' > 0`). From guesses where `h' > 0` the
    /// closed form's root is the second, from those where `h' < 0` the first, whichever Newton
    /// reaches (`modes` names the block): from `0.44`, just short of the axis `atan(1/2)` where
    /// `h'` changes sign, Newton alone reached `π/2`.
    #[test]
    fn an_angle_equation_keeps_the_guess_s_root() {
        let k = 1e200;
        let at = |q: &[f64; 1], ev: &mut BlockEval<1, 0>| {
            ev.f = [2.0 * k * q[0].cos() + k * q[0].sin() - k];
            ev.j = [[-2.0 * k * q[0].sin() + k * q[0].cos()]];
        };
        let modes = [Block { rows: vec![0], cols: vec![0], closed_form: true }];
        let (up, down) = (core::f64::consts::FRAC_PI_2, -(0.75f64).atan());
        for g in [-2.0, -1.0, 0.0, 0.3, 0.4, 0.44, 0.48, 0.52, 0.6, 1.0, 2.0, 3.0] {
            let root = unwrap_to_turn(if f64::cos(g) - 2.0 * f64::sin(g) > 0.0 { down } else { up }, g);
            let (q, _) =
                whole_position(&[g], [4.0 * k], [1.0], [true], &NewtonConfig::default(), AtLimit::Singular, &modes, at)
                    .unwrap_or_else(|f| panic!("from {g}: {f:?}"));
            // On the guess's turn, as the closed form's, within a few ulps: the rounding of terms
            // of magnitude 4 over `|h'| = sqrt(5)` at either root.
            assert!((q[0] - root).abs() < 1e-14, "from {g}: {} against {root}", q[0]);
        }
    }

    /// The same angle equation with a slider `s` of fixed direction, times `1e200`:
    /// `F0 = 2 cos q + sin q - 1`, `F1 = cos q - sin q / 2 + s`, mixed (`G0 = F0 + F1 / 2`,
    /// `G1 = F1 - 0.3 F0`, so that both rows hold `s`: `m (cos q, sin q) + d s + e = 0`). The
    /// slider-free combination is `F0` again, and the determinant `1.15 F0'`: the closed form's
    /// root is the one of `F0` where `h'` has the guess's sign, `s` from `F1`. From 900 guesses
    /// (`q` every 0.02 rad of a turn, `s` 0, 3 or -3) Newton alone reached the other root from
    /// 55 (`closed_form` off; at least 10 asserted below, so that the test is of the mirror).
    #[test]
    fn an_angle_and_a_slider_keep_the_guess_s_root() {
        let k = 1e200;
        let at = |z: &[f64; 2], ev: &mut BlockEval<2, 0>| {
            let (c, s) = (z[0].cos(), z[0].sin());
            let f = [2.0 * c + s - 1.0, c - s / 2.0 + z[1]];
            let df = [[-2.0 * s + c, 0.0], [-s - c / 2.0, 1.0]];
            ev.f = [k * (f[0] + f[1] / 2.0), k * (f[1] - 0.3 * f[0])];
            ev.j = [
                [k * (df[0][0] + df[1][0] / 2.0), k * df[1][1] / 2.0],
                [k * (df[1][0] - 0.3 * df[0][0]), k * df[1][1]],
            ];
        };
        let (up, down) = (core::f64::consts::FRAC_PI_2, -(0.75f64).atan());
        let solve = |guess: [f64; 2], closed_form: bool| {
            let blocks = [Block { rows: vec![0, 1], cols: vec![0, 1], closed_form }];
            let cfg = NewtonConfig::default();
            whole_position(&guess, [6.0 * k; 2], [1.0, 1.0], [true, false], &cfg, AtLimit::Singular, &blocks, at)
                .unwrap_or_else(|f| panic!("from {guess:?}: {f:?}"))
                .0
        };
        let mut other = 0;
        for s0 in [0.0, 3.0, -3.0] {
            for i in 0..300 {
                let g = -3.0 + 0.02 * f64::from(i);
                let root = unwrap_to_turn(if f64::cos(g) - 2.0 * f64::sin(g) > 0.0 { down } else { up }, g);
                let q = solve([g, s0], true);
                // The root's rounding over `|h'| = sqrt(5)`, and the slider's from it.
                assert!((q[0] - root).abs() < 1e-14, "from {g}, {s0}: {} against {root}", q[0]);
                let s = -(root.cos() - root.sin() / 2.0);
                assert!((q[1] - s).abs() < 1e-14, "from {g}, {s0}: {} against {s}", q[1]);
                other += usize::from((solve([g, s0], false)[0] - root).abs() > 0.1);
            }
        }
        assert!(other >= 10, "{other} solves in the other mode with the modes not kept");
    }

    /// A dyad's rows in any order and sign: the four-bar's loop `a e^(i phi) + b e^(i beta) =
    /// (d, 0) + c e^(i gamma)` (crank 1, coupler 3.5, rocker 3, frame 4, at `phi = 1`) times
    /// `1e200`, its rows given as `(x, y)`, `(y, x)`, `(-x, y)` and `(-y, -x)`. The mirror reflects
    /// the links across the line of the centres' offset and turns each angle by twice its
    /// distance from it, with signs read from the rows (`det_sign`): a reflection or a negation
    /// of the rows flips both the angles' differences and the links' turning signs, so that the
    /// image is the same. From 49 guesses over a turn of each angle, each ordering gives the root
    /// whose determinant has the guess's sign (both roots by the circles' intersection), where
    /// Newton alone reached the other from 22 (at least 10 asserted: the mirror is tried).
    #[test]
    fn a_dyad_keeps_the_guess_s_root_whatever_its_rows() {
        let k = 1e200;
        let (a, b, c, d, phi) = (1.0, 3.5, 3.0, 4.0, 1.0f64);
        // The loop's residual and its derivatives by `beta` and `gamma`, as `(x, y)`.
        let loop_at = |z: &[f64; 2]| {
            let f =
                [a * phi.cos() + b * z[0].cos() - d - c * z[1].cos(), a * phi.sin() + b * z[0].sin() - c * z[1].sin()];
            let j = [[-b * z[0].sin(), c * z[1].sin()], [b * z[0].cos(), -c * z[1].cos()]];
            (f, j)
        };
        // The two roots: the coupler's end `p` on both circles, about the crank's end `A` (radius
        // `b`) and the rocker's pivot `D` (radius `c`).
        let (ax, ay) = (a * phi.cos(), a * phi.sin());
        let (ex, ey) = (d - ax, -ay);
        let e = ex.hypot(ey);
        let along = (b * b - c * c + e * e) / (2.0 * e);
        let across = (b * b - along * along).sqrt();
        let roots = [1.0, -1.0].map(|side: f64| {
            let (px, py) = (ax + (along * ex - side * across * ey) / e, ay + (along * ey + side * across * ex) / e);
            [(py - ay).atan2(px - ax), py.atan2(px - d)]
        });
        let det = |rows: [(usize, f64); 2], z: &[f64; 2]| {
            let (_, j) = loop_at(z);
            let r = rows.map(|(i, sign)| j[i].map(|v| sign * v));
            r[0][0] * r[1][1] - r[0][1] * r[1][0]
        };
        for rows in [[(0, 1.0), (1, 1.0)], [(1, 1.0), (0, 1.0)], [(0, -1.0), (1, 1.0)], [(1, -1.0), (0, -1.0)]] {
            let at = |z: &[f64; 2], ev: &mut BlockEval<2, 0>| {
                let (f, j) = loop_at(z);
                ev.f = rows.map(|(i, sign)| k * sign * f[i]);
                ev.j = rows.map(|(i, sign)| j[i].map(|v| k * sign * v));
            };
            let mut other = 0;
            let grid = (0..49).map(|i| [f64::from(i / 7) - 2.9, f64::from(i % 7) - 3.1]);
            for guess in grid {
                let want = det(rows, &guess).signum();
                let root = roots.iter().find(|r| det(rows, r).signum() == want).expect("a root of each sign");
                let root = [0, 1].map(|u| unwrap_to_turn(root[u], guess[u]));
                let solve = |closed_form: bool| {
                    let blocks = [Block { rows: vec![0, 1], cols: vec![0, 1], closed_form }];
                    let cfg = NewtonConfig::default();
                    whole_position(&guess, [11.5 * k; 2], [1.0; 2], [true; 2], &cfg, AtLimit::Singular, &blocks, at)
                        .unwrap_or_else(|f| panic!("rows {rows:?} from {guess:?}: {f:?}"))
                        .0
                };
                let q = solve(true);
                // The angles' rounding through the dyad's determinant (its links 3.5 and 3
                // about 0.4 rad from folding): a few ulps.
                let off = |q: [f64; 2]| (q[0] - root[0]).abs().max((q[1] - root[1]).abs());
                assert!(off(q) < 1e-13, "rows {rows:?} from {guess:?}: {q:?} against {root:?}");
                other += usize::from(off(solve(false)) > 0.1);
            }
            assert!(other >= 10, "rows {rows:?}: {other} solves in the other mode with the modes not kept");
        }
    }
}
