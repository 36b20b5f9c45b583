//! The closed-form solve of a recognised block at run time: the operations the emitter's
//! `closed_form` writes, in the same order, on values instead of tokens.
//!
//! The emitter folds the coefficients that are constants of the graph while it writes the
//! solve (a link along an axis costs no multiplication) and picks other formulas when a
//! coefficient is the constant zero. [`V`] keeps that distinction at run time: a constant
//! folds by the emitter's rules, any other value is computed as the emitted expression would
//! compute it. The runtime's functions (`dyad_roots`, `root_offset`, `unwrap_to_turn`, ...) are
//! called as the emitted code calls them, so the angles, sines and cosines are the compiled
//! mechanism's.

use kinloop_codegen::graph::dag::{Graph, NodeId};
use kinloop_codegen::plan::closed_form::ClosedForm;
use kinloop_runtime::NewtonConfig;
use kinloop_runtime::generated::{
    BlockFailure, acos_on_side, asin_near, check_closed, check_guess, dyad_roots, half_turn_if, polar_norm,
    reduce_turn, root_offset, sign_at_guess, unwrap_to_turn,
};
use std::f64::consts::FRAC_PI_2;

/// A value of the solve: a constant of the graph (folded as the emitter folds it) or a value
/// computed at run time.
#[derive(Clone, Copy, Debug)]
enum V {
    C(f64),
    E(f64),
}

impl V {
    fn val(self) -> f64 {
        match self {
            V::C(x) | V::E(x) => x,
        }
    }

    fn is_zero(self) -> bool {
        matches!(self, V::C(z) if z == 0.0)
    }
}

fn neg(a: V) -> V {
    match a {
        V::C(x) => V::C(-x),
        V::E(t) => V::E(-t),
    }
}

fn mul(a: V, b: V) -> V {
    match (a, b) {
        (V::C(x), V::C(y)) => V::C(x * y),
        _ if a.is_zero() || b.is_zero() => V::C(0.0),
        (V::C(o), e) | (e, V::C(o)) if o == 1.0 => e,
        (V::C(m), e) | (e, V::C(m)) if m == -1.0 => neg(e),
        _ => V::E(a.val() * b.val()),
    }
}

fn add(a: V, b: V) -> V {
    match (a, b) {
        (V::C(x), V::C(y)) => V::C(x + y),
        (V::C(0.0), e) | (e, V::C(0.0)) => e,
        _ => V::E(a.val() + b.val()),
    }
}

fn sub(a: V, b: V) -> V {
    match (a, b) {
        (V::C(x), V::C(y)) => V::C(x - y),
        (e, V::C(0.0)) => e,
        (V::C(0.0), e) => neg(e),
        _ => V::E(a.val() - b.val()),
    }
}

fn abs(a: V) -> V {
    match a {
        V::C(x) => V::C(x.abs()),
        V::E(t) => V::E(t.abs()),
    }
}

/// `a · x` for pairs `(a, x)`, summed from zero as the emitter does.
fn dot(terms: &[(V, V)]) -> V {
    terms.iter().fold(V::C(0.0), |acc, &(a, x)| add(acc, mul(a, x)))
}

/// Reads a block's coefficients: a constant node as a constant, any other from its register.
struct Read<'a> {
    g: &'a Graph,
    r: &'a [f64],
}

impl Read<'_> {
    #[inline(always)]
    fn v(&self, n: NodeId) -> V {
        match self.g.as_const(n) {
            Some(c) => V::C(c),
            None => V::E(self.r[n.index()]),
        }
    }

    /// Written out: `array::map` is not always inlined, and this runs on every step.
    #[inline(always)]
    fn m(&self, m: &[[NodeId; 2]; 2]) -> [[V; 2]; 2] {
        [[self.v(m[0][0]), self.v(m[0][1])], [self.v(m[1][0]), self.v(m[1][1])]]
    }
}

/// What a closed-form solve produced: the angles, then the length or slider, then each angle's
/// cosine and sine (the emitter's `__out` array), `len` values of it.
pub(crate) struct Out {
    pub(crate) values: [f64; 6],
    pub(crate) len: usize,
}

/// Solves the block of `form` from the coefficients in the registers `r` and the guesses.
pub(crate) fn solve(
    form: &ClosedForm,
    g: &Graph,
    r: &[f64],
    guess: &[f64],
    cfg: &NewtonConfig,
) -> Result<Out, BlockFailure> {
    let rd = Read { g, r };
    // The guess of a length or slider only picks the branch, through comparisons: checked first.
    let others = match form {
        ClosedForm::PolarLength { length, .. } => Some(*length),
        ClosedForm::AngleSlider { slider, .. } => Some(*slider),
        ClosedForm::AngleEquation { .. } | ClosedForm::Dyad { .. } => None,
    };
    if let Some(o) = others {
        // The angle's guess, then the other's (the forms with a length or slider have one angle).
        let angle = match form {
            ClosedForm::PolarLength { angle, .. } | ClosedForm::AngleSlider { angle, .. } => *angle,
            ClosedForm::AngleEquation { angle, .. } => *angle,
            ClosedForm::Dyad { angles, .. } => angles[0],
        };
        check_guess(guess[angle] + guess[o])?;
    }
    let (values, len) = match form {
        ClosedForm::AngleEquation { angle, a, b, c } => {
            let out = angle_equation(rd.v(*a), rd.v(*b), rd.v(*c), guess[*angle], cfg)?;
            check_closed(&out, 1, cfg)?;
            ([out[0], out[1], out[2], 0.0, 0.0, 0.0], 3)
        }
        ClosedForm::Dyad { angles, m, reflect, e } => {
            let out = dyad(&rd.m(&m[0]), &rd.m(&m[1]), *reflect, [rd.v(e[0]), rd.v(e[1])], *angles, guess, cfg)?;
            check_closed(&out, 2, cfg)?;
            (out, 6)
        }
        ClosedForm::PolarLength { angle, length, w, e } => {
            let out = polar(&rd.m(w), [rd.v(e[0]), rd.v(e[1])], guess[*angle], guess[*length], cfg)?;
            check_closed(&out, 1, cfg)?;
            ([out[0], out[1], out[2], out[3], 0.0, 0.0], 4)
        }
        ClosedForm::AngleSlider { angle, m, d, e, .. } => {
            let out = angle_slider(&rd.m(m), [rd.v(d[0]), rd.v(d[1])], [rd.v(e[0]), rd.v(e[1])], guess[*angle], cfg)?;
            check_closed(&out, 1, cfg)?;
            ([out[0], out[1], out[2], out[3], 0.0, 0.0], 4)
        }
    };
    Ok(Out { values, len })
}

/// The root `(cos q, sin q)` of `a cos q + b sin q = c` on the side `flip` picks.
fn root(a: V, b: V, c: V, flip: bool, cfg: &NewtonConfig) -> Result<(f64, f64), BlockFailure> {
    if let (V::E(a), V::E(b), V::E(c)) = (a, b, c) {
        return dyad_roots(a, b, c, flip, cfg);
    }
    let r2 = add(mul(a, a), mul(b, b));
    let d2 = sub(r2, mul(c, c));
    let d = V::E(root_offset(d2.val(), r2.val(), c.val(), flip, cfg)?);
    let (cq, sq) = if a.is_zero() {
        let ib = V::E(1.0 / b.val());
        (neg(mul(d, ib)), mul(c, ib))
    } else if b.is_zero() {
        let ia = V::E(1.0 / a.val());
        (mul(c, ia), mul(d, ia))
    } else {
        let inv = V::E(1.0 / r2.val());
        (mul(sub(mul(a, c), mul(b, d)), inv), mul(add(mul(b, c), mul(a, d)), inv))
    };
    Ok((cq.val(), sq.val()))
}

/// The sign rule at the guess `g` (the emitter's `flip_at_guess`).
fn flip_at_guess(a: V, b: V, g: f64) -> bool {
    if a.is_zero() {
        (b.val() > 0.0) == (reduce_turn(g).abs() < FRAC_PI_2)
    } else if b.is_zero() {
        (a.val() > 0.0) == (reduce_turn(g) < 0.0)
    } else {
        let bound = add(abs(a), abs(b)).val();
        let (av, bv) = (a.val(), b.val());
        sign_at_guess(g, 3.0 * bound, |(sg, cg)| bv * cg - av * sg) > 0.0
    }
}

fn angle_equation(a: V, b: V, c: V, g: f64, cfg: &NewtonConfig) -> Result<[f64; 3], BlockFailure> {
    if a.is_zero() {
        let r = reduce_turn(g);
        let right = r.abs() < FRAC_PI_2;
        let flip = (b.val() > 0.0) == right;
        let (cq, sq) = root(a, b, c, flip, cfg)?;
        return Ok([asin_near(sq, right, r, g), cq, sq]);
    }
    let flip = flip_at_guess(a, b, g);
    let (cq, sq) = root(a, b, c, flip, cfg)?;
    let q = if b.is_zero() { unwrap_to_turn(acos_on_side(cq, sq), g) } else { unwrap_to_turn(sq.atan2(cq), g) };
    Ok([q, cq, sq])
}

fn dyad(
    a: &[[V; 2]; 2],
    b: &[[V; 2]; 2],
    reflect: [bool; 2],
    e: [V; 2],
    angles: [usize; 2],
    guess: &[f64],
    cfg: &NewtonConfig,
) -> Result<[f64; 6], BlockFailure> {
    let (g0, g1) = (guess[angles[0]], guess[angles[1]]);
    let k = |i: usize, j: usize| sub(mul(a[0][i], b[1][j]), mul(a[1][i], b[0][j]));
    let (k00, k01) = (k(0, 0), k(0, 1));
    let sigma = if reflect[0] == reflect[1] { g1 - g0 } else { g1 + g0 };
    let (ca, cb) = if reflect[0] { (neg(k01), k00) } else { (k01, neg(k00)) };
    let flip = if cb.is_zero() { (ca.val() * reduce_turn(sigma)) < 0.0 } else { flip_at_guess(ca, cb, sigma) };
    let ca = dot(&[(a[0][0], e[0]), (a[1][0], e[1])]);
    let cb = dot(&[(a[0][1], e[0]), (a[1][1], e[1])]);
    let l0 = dot(&[(a[0][0], a[0][0]), (a[1][0], a[1][0])]);
    let l1 = dot(&[(b[0][0], b[0][0]), (b[1][0], b[1][0])]);
    let ee = dot(&[(e[0], e[0]), (e[1], e[1])]);
    let cc = mul(V::C(0.5), sub(sub(l1, l0), ee));
    let (cq, sq) = root(ca, cb, cc, flip, cfg)?;
    let (cqv, sqv) = (V::E(cq), V::E(sq));
    let vx = add(e[0], dot(&[(a[0][0], cqv), (a[0][1], sqv)]));
    let vy = add(e[1], dot(&[(a[1][0], cqv), (a[1][1], sqv)]));
    let il1 = V::E(-1.0 / l1.val());
    let c1 = mul(dot(&[(b[0][0], vx), (b[1][0], vy)]), il1).val();
    let s1 = mul(dot(&[(b[0][1], vx), (b[1][1], vy)]), il1).val();
    let q0 = unwrap_to_turn(sq.atan2(cq), g0);
    let q1 = unwrap_to_turn(s1.atan2(c1), g1);
    Ok([q0, q1, cq, sq, c1, s1])
}

/// `|w (cos q, sin q)|²` when it is the same constant for every `q` (the emitter's rule).
fn constant_norm2(w: &[[V; 2]; 2]) -> Option<f64> {
    let [[V::C(a), V::C(b)], [V::C(c), V::C(d)]] = *w else {
        return None;
    };
    let (n0, n1) = (a * a + c * c, b * b + d * d);
    (a * b + c * d == 0.0 && n0 == n1).then_some(n0)
}

fn polar(w: &[[V; 2]; 2], e: [V; 2], g: f64, gs: f64, cfg: &NewtonConfig) -> Result<[f64; 4], BlockFailure> {
    let a = sub(mul(w[0][0], e[1]), mul(w[1][0], e[0]));
    let b = sub(mul(w[0][1], e[1]), mul(w[1][1], e[0]));
    let r2 = add(mul(a, a), mul(b, b));
    let q0 = (-a.val()).atan2(b.val());
    let ir = V::E(polar_norm(r2.val(), e[0].val(), e[1].val(), cfg)?);
    let (mut cq, mut sq) = (mul(b, ir).val(), neg(mul(a, ir)).val());
    let (cqv, sqv) = (V::E(cq), V::E(sq));
    let w0 = dot(&[(w[0][0], cqv), (w[0][1], sqv)]);
    let w1 = dot(&[(w[1][0], cqv), (w[1][1], sqv)]);
    let num = dot(&[(w0, e[0]), (w1, e[1])]);
    let mut s = match constant_norm2(w) {
        Some(1.0) => neg(num).val(),
        Some(k2) => -num.val() / k2,
        None => {
            let den = dot(&[(w0, w0), (w1, w1)]);
            -num.val() / den.val()
        }
    };
    let flip = s * gs < 0.0;
    if flip {
        s = -s;
        cq = -cq;
        sq = -sq;
    }
    Ok([unwrap_to_turn(half_turn_if(q0, flip), g), s, cq, sq])
}

fn angle_slider(m: &[[V; 2]; 2], d: [V; 2], e: [V; 2], g: f64, cfg: &NewtonConfig) -> Result<[f64; 4], BlockFailure> {
    let a = sub(mul(d[1], m[0][0]), mul(d[0], m[1][0]));
    let b = sub(mul(d[1], m[0][1]), mul(d[0], m[1][1]));
    let c = sub(mul(d[0], e[1]), mul(d[1], e[0]));
    let flip = flip_at_guess(a, b, g);
    let (cq, sq) = root(a, b, c, flip, cfg)?;
    let (cqv, sqv) = (V::E(cq), V::E(sq));
    let r0 = add(dot(&[(m[0][0], cqv), (m[0][1], sqv)]), e[0]);
    let r1 = add(dot(&[(m[1][0], cqv), (m[1][1], sqv)]), e[1]);
    let num = dot(&[(d[0], r0), (d[1], r1)]);
    let den = dot(&[(d[0], d[0]), (d[1], d[1])]);
    let q = unwrap_to_turn(sq.atan2(cq), g);
    Ok([q, -num.val() / den.val(), cq, sq])
}
