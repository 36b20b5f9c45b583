//! The closed-form solve of a recognised block at run time: the operations the emitter's
//! `closed_form` writes, in the same order, compiled when the model is built into a small
//! program over the registers.
//!
//! The emitter folds the coefficients that are constants of the graph while it writes the
//! solve (a link along an axis costs no multiplication) and picks other formulas when a
//! coefficient is the constant zero. Those decisions depend only on the graph's constants, so
//! they are made once, here, by the same rules on [`V`] (a constant folds, a register is
//! computed as the emitted expression computes it), and what remains is a list of [`Op`]s:
//! straight arithmetic over registers and calls of the runtime's functions (`dyad_roots`,
//! `folded_root_offset`, `polar_norm`, the flip rules, `unwrap_to_turn`, ...) as the emitted code calls
//! them, so the angles, sines and cosines are the compiled mechanism's to the last bit.
//!
//! Each form's arithmetic is one function below ([`Build::angle_equation`], [`Build::dyad`],
//! [`Build::polar`], [`Build::angle_slider`]), beside the emitter's function of the same name.

use crate::extra::Extra;
use crate::tape::{Chains, Ins, Segment};
use kinloop_codegen::graph::dag::{self, Graph, Leaf, NodeId};
use kinloop_codegen::plan::closed_form::{ClosedForm, constant_norm2};
use kinloop_runtime::NewtonConfig;
use kinloop_runtime::generated::{
    BlockFailure, acos_on_side, asin_near, check_closed, check_guess, dyad_d2, dyad_of, dyad_roots_in,
    folded_dyad_root_offset, folded_root_offset_in, half_turn_if, polar_norm, reduce_turn, root_offset_deferred,
    sign_at_guess, unwrap_to_turn,
};
use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;

/// One operation of a closed form's program, on registers (`u32` indices, checked once when
/// the program is built). A flag (a root's side) is a register holding 1 or 0.
#[derive(Clone, Copy, Debug)]
enum Op {
    Add(u32, u32, u32),
    Sub(u32, u32, u32),
    Mul(u32, u32, u32),
    Div(u32, u32, u32),
    Neg(u32, u32),
    Abs(u32, u32),
    Mov(u32, u32),
    /// `r[d] = guess[u]`.
    Guess(u32, u32),
    /// `check_guess(a + b)`.
    CheckGuess(u32, u32),
    /// `[r, right, flip]` of the guess `g` of `b sin q = c`: `r = reduce_turn(g)`, `right =
    /// |r| < π/2`, `flip = (b > 0) == right` (the emitter's `angle_equation` with `a` zero).
    Side {
        r: u32,
        right: u32,
        flip: u32,
        b: u32,
        g: u32,
    },
    /// `flip = (b > 0) == (|reduce_turn(g)| < π/2)` (`flip_at_guess` with `a` zero).
    FlipZeroA {
        flip: u32,
        b: u32,
        g: u32,
    },
    /// `flip = (a > 0) == (reduce_turn(g) < 0)` (`flip_at_guess` with `b` zero).
    FlipZeroB {
        flip: u32,
        a: u32,
        g: u32,
    },
    /// `flip = sign_at_guess(g, 3 bound, |(s, c)| b c - a s) > 0` (`flip_at_guess`).
    FlipSign {
        flip: u32,
        a: u32,
        b: u32,
        bound: u32,
        g: u32,
    },
    /// `flip = a reduce_turn(g) < 0` (the dyad's rule when its `b` is zero).
    FlipProduct {
        flip: u32,
        a: u32,
        g: u32,
    },
    /// `(cq, sq) = dyad_roots_in(a, b, c, flip, terms)`: a form of one angle's, a failure judged
    /// again in the magnitude of its equation's terms.
    DyadRoots {
        cq: u32,
        sq: u32,
        a: u32,
        b: u32,
        c: u32,
        flip: u32,
    },
    /// `(cq, sq) = dyad_of([a, b, e0, e1, l0, l1], c, flip)`: a dyad's.
    DyadRootsOf {
        cq: u32,
        sq: u32,
        a: u32,
        b: u32,
        c: u32,
        e0: u32,
        e1: u32,
        l0: u32,
        l1: u32,
        flip: u32,
    },
    /// `d = dyad_d2(d2, r2, [e0, e1, l0, l1])`: a dyad's `d2` with a coefficient folded.
    DyadD2 {
        d: u32,
        d2: u32,
        r2: u32,
        e0: u32,
        e1: u32,
        l0: u32,
        l1: u32,
    },
    /// `d = folded_root_offset(d2, r2, a, b, c, flip)`.
    RootOffset {
        d: u32,
        d2: u32,
        r2: u32,
        a: u32,
        b: u32,
        c: u32,
        flip: u32,
    },
    /// `d = polar_norm(r2, e0, e1)`.
    PolarNorm {
        d: u32,
        r2: u32,
        e0: u32,
        e1: u32,
    },
    /// A polar length's half turn: `s`, `cq`, `sq` negated when `s gs < 0`.
    PolarSide {
        s: u32,
        cq: u32,
        sq: u32,
        gs: u32,
    },
    /// `d = s.atan2(c)`.
    Atan2 {
        d: u32,
        s: u32,
        c: u32,
    },
    /// A polar angle: `d = unwrap_to_turn(half_turn_if(q0, s gs < 0), g)`, read before
    /// [`Op::PolarSide`] negates `s`.
    PolarAngle {
        d: u32,
        q0: u32,
        s: u32,
        gs: u32,
        g: u32,
    },
    /// `d = unwrap_to_turn(s.atan2(c), g)`.
    Atan2Unwrap {
        d: u32,
        s: u32,
        c: u32,
        g: u32,
    },
    /// `d = unwrap_to_turn(acos_on_side(c, s), g)`.
    AcosUnwrap {
        d: u32,
        c: u32,
        s: u32,
        g: u32,
    },
    /// `d = asin_near(s, right, r, g)`.
    AsinNear {
        d: u32,
        s: u32,
        right: u32,
        r: u32,
        g: u32,
    },
    /// The chain of `ClosedProg::runs` starting at this step: consecutive [`Op::Add`] ...
    /// [`Op::Neg`] executed as the tape executes them (up to four operations a dispatch).
    Run(u32),
    /// `check_closed(out[..len], angles)`.
    Check {
        out: [u32; 6],
        len: u8,
        angles: u8,
    },
}

impl Op {
    /// Every register the operation names, for renaming and for the bound check (a guess's
    /// index is not a register).
    fn registers_mut(&mut self) -> Vec<&mut u32> {
        match self {
            Op::Add(d, a, b) | Op::Sub(d, a, b) | Op::Mul(d, a, b) | Op::Div(d, a, b) => vec![d, a, b],
            Op::Neg(d, a) | Op::Abs(d, a) | Op::Mov(d, a) | Op::CheckGuess(d, a) => vec![d, a],
            Op::Guess(d, _) => vec![d],
            Op::Side { r, right, flip, b, g } => vec![r, right, flip, b, g],
            Op::FlipZeroA { flip, b: x, g } | Op::FlipZeroB { flip, a: x, g } | Op::FlipProduct { flip, a: x, g } => {
                vec![flip, x, g]
            }
            Op::FlipSign { flip, a, b, bound, g } => vec![flip, a, b, bound, g],
            Op::DyadRoots { cq, sq, a, b, c, flip } => vec![cq, sq, a, b, c, flip],
            Op::DyadRootsOf { cq, sq, a, b, c, e0, e1, l0, l1, flip } => vec![cq, sq, a, b, c, e0, e1, l0, l1, flip],
            Op::DyadD2 { d, d2, r2, e0, e1, l0, l1 } => vec![d, d2, r2, e0, e1, l0, l1],
            Op::RootOffset { d, d2, r2, a, b, c, flip } => vec![d, d2, r2, a, b, c, flip],
            Op::PolarNorm { d, r2, e0, e1 } => vec![d, r2, e0, e1],
            Op::PolarSide { s, cq, sq, gs } => vec![s, cq, sq, gs],
            Op::Atan2 { d, s, c } => vec![d, s, c],
            Op::PolarAngle { d, q0, s, gs, g } => vec![d, q0, s, gs, g],
            Op::Atan2Unwrap { d, s, c, g } | Op::AcosUnwrap { d, c, s, g } => vec![d, s, c, g],
            Op::AsinNear { d, s, right, r, g } => vec![d, s, right, r, g],
            Op::Check { out, len, .. } => out[..*len as usize].iter_mut().collect(),
            // Made when the program is complete, from operations already counted.
            Op::Run(_) => Vec::new(),
        }
    }

    /// The operation as a tape instruction, if it is arithmetic.
    fn arith(self) -> Option<Ins> {
        match self {
            Op::Add(d, a, b) => Some(Ins::Add(d, a, b)),
            Op::Sub(d, a, b) => Some(Ins::Sub(d, a, b)),
            Op::Mul(d, a, b) => Some(Ins::Mul(d, a, b)),
            Op::Div(d, a, b) => Some(Ins::Div(d, a, b)),
            Op::Neg(d, a) => Some(Ins::Neg(d, a)),
            _ => None,
        }
    }
}

/// The operations with each run of two or more consecutive arithmetic operations replaced by
/// [`Op::Run`]s of the returned chains (the same operations in the same order; a single one
/// stays, one dispatch either way).
fn runs(ops: Vec<Op>) -> (Vec<Op>, Chains) {
    let mut out = Vec::with_capacity(ops.len());
    let mut chains = Chains::default();
    let mut k = 0;
    while k < ops.len() {
        let run: Vec<Ins> = ops[k..].iter().map_while(|o| o.arith()).collect();
        if run.len() >= 2 {
            k += run.len();
            out.extend(chains.push(&run).into_iter().map(Op::Run));
        } else {
            out.push(ops[k]);
            k += 1;
        }
    }
    (out, chains)
}

/// A closed form compiled: its operations, and where its solution is left.
#[derive(Clone, Debug)]
pub(crate) struct ClosedProg {
    ops: Vec<Op>,
    /// The runs of arithmetic operations ([`Op::Run`]).
    runs: Chains,
    /// One more than the largest register named: the registers a run needs.
    needs: usize,
    /// One more than the largest guess read.
    guesses: usize,
    /// The unknowns in the order the solve gives them (the angles, then the length or slider),
    /// each with the register that holds its value after a run (its leaf's when it has one).
    pub(crate) unknowns: Vec<(usize, u32)>,
    /// For a form solved from one equation of its angle alone, the magnitude of that
    /// equation's terms (the plan's `terms`): the segment computing it from what the solves
    /// before the block wrote, and its register. Run only where the root fails, as the
    /// compiled solve computes it there (`folded_root_offset_in`, `dyad_roots_in`).
    terms: Option<(Segment, u32)>,
}

impl ClosedProg {
    /// Compiles the solve of `form` over the graph `g`: `sin_cos` are the registers of each
    /// angle's `[sin, cos]` nodes (where the solve leaves its values; a fresh register for a
    /// missing one). Each unknown's value is left in its leaf's register, a fresh one for an
    /// unknown the graph does not read.
    pub(crate) fn build(form: &ClosedForm, g: &Graph, sin_cos: &[[Option<u32>; 2]], extra: &mut Extra) -> ClosedProg {
        let mut b = Build { g, extra, ops: Vec::new(), temps: HashMap::new(), guess_regs: HashMap::new() };
        let order = form.solve_order();
        // The targets of the solution's values, in the order of the emitter's `__out`.
        let mut targets: Vec<u32> = order
            .iter()
            .map(|&u| g.find(dag::Op::Leaf(Leaf::Unknown(u as u16))).map_or_else(|| b.extra.fresh(), |n| n.0))
            .collect();
        for [s, c] in sin_cos {
            for t in [c, s] {
                targets.push(t.unwrap_or_else(|| b.extra.fresh()));
            }
        }
        // The guess of a length or slider only picks the branch, through comparisons: checked
        // first, with the angle's (the forms with a length or slider have one angle).
        if let [angle, other] = order[..] {
            let (ga, go) = (b.guess(angle), b.guess(other));
            b.ops.push(Op::CheckGuess(ga, go));
        }
        let out: Vec<V> = match form {
            ClosedForm::AngleEquation { angle, a, b: bb, c } => {
                let (a, bb, c) = (b.v(*a), b.v(*bb), b.v(*c));
                b.angle_equation(a, bb, c, *angle).to_vec()
            }
            ClosedForm::Dyad { angles, m, reflect, e } => {
                let (m0, m1, e) = (b.m(&m[0]), b.m(&m[1]), [b.v(e[0]), b.v(e[1])]);
                b.dyad(&m0, &m1, *reflect, e, *angles, &targets).to_vec()
            }
            ClosedForm::PolarLength { angle, length, w, e } => {
                let (w, e) = (b.m(w), [b.v(e[0]), b.v(e[1])]);
                b.polar(&w, e, *angle, *length, &targets).to_vec()
            }
            ClosedForm::AngleSlider { angle, m, d, e, .. } => {
                let (m, d, e) = (b.m(m), [b.v(d[0]), b.v(d[1])], [b.v(e[0]), b.v(e[1])]);
                b.angle_slider(&m, d, e, *angle).to_vec()
            }
        };
        debug_assert_eq!(out.len(), targets.len());
        let placed: Vec<u32> = out.into_iter().zip(&targets).map(|(v, &t)| b.place(v, t)).collect();
        let mut check = [0; 6];
        check[..placed.len()].copy_from_slice(&placed);
        b.ops.push(Op::Check { out: check, len: placed.len() as u8, angles: form.angles().len() as u8 });
        let mut ops = b.ops;
        let needs = ops.iter_mut().flat_map(|o| o.registers_mut().into_iter().map(|r| *r)).max().map_or(0, |m| m + 1);
        let guesses = ops.iter().filter_map(|o| if let Op::Guess(_, u) = o { Some(*u + 1) } else { None }).max();
        let (ops, runs) = runs(ops);
        // The runs' registers are the program's; the larger of the two, so that the one test in
        // `run` covers what the unsafe `Op::Run` reads whatever a pass renames.
        let needs = (needs as usize).max(runs.needs());
        ClosedProg {
            ops,
            runs,
            needs,
            guesses: guesses.unwrap_or(0) as usize,
            unknowns: order.into_iter().zip(placed).collect(),
            terms: None,
        }
    }

    /// Gives the program the segment computing the magnitude of its equation's terms into
    /// register `at` (see `ClosedProg::terms`). The registers a run needs cover the segment's,
    /// so that the one test of `run` covers what it writes on the cold path.
    pub(crate) fn with_terms(mut self, seg: Segment, at: u32) -> ClosedProg {
        self.needs = self.needs.max(seg.needs()).max(at as usize + 1);
        self.terms = Some((seg, at));
        self
    }

    /// The magnitude of the terms of the block's equation (see `ClosedProg::terms`), computed
    /// from the registers at `p` as the compiled solve computes it, where the root fails (the
    /// runtime's `folded_root_offset_in`, `dyad_roots_in` call it only there); NaN for a form
    /// without it, which leaves the failure as it is.
    ///
    /// # Safety
    /// `p` points to at least `self.needs` registers, which nothing else reads or writes
    /// during the call.
    #[cold]
    #[inline(never)]
    unsafe fn terms_at(&self, p: *mut f64) -> f64 {
        let Some((seg, at)) = &self.terms else { return f64::NAN };
        // SAFETY: the caller's: `needs` covers the segment's registers (`with_terms`).
        let r = unsafe { std::slice::from_raw_parts_mut(p, self.needs) };
        seg.run(r);
        r[*at as usize]
    }

    /// `RootOffset`'s cold path, where its test fails (registers at `p`: `d2`, the coefficients
    /// `a`, `b`, `c`; `r2` its value): `folded_dyad_root_offset` for a dyad's root (its `d2`
    /// written by a `DyadD2`, every register having one writer), with the residual of one that
    /// cannot be assembled in its links' lengths; `folded_root_offset_in` for another (a failure
    /// judged again in the magnitude of its equation's terms, `ClosedProg::terms_at`). Out of line:
    /// inlined, it took the run's loop 44 instructions a step more on a rhombic drive, which
    /// never comes here.
    ///
    /// # Safety
    /// Every register of the program is below the length of the registers at `p`.
    #[cold]
    #[inline(never)]
    unsafe fn off_range(
        &self,
        p: *mut f64,
        [d2, a, b, c]: [u32; 4],
        r2: f64,
        flip: bool,
        cfg: &NewtonConfig,
    ) -> Result<f64, BlockFailure> {
        // SAFETY: the caller's.
        let v = |k: u32| unsafe { *p.add(k as usize) };
        let links = self.ops.iter().find_map(|op| match *op {
            Op::DyadD2 { d, e0, e1, l0, l1, .. } if d == d2 => Some([v(e0), v(e1), v(l0), v(l1)]),
            _ => None,
        });
        match links {
            Some(links) => folded_dyad_root_offset(v(d2), r2, v(a), v(b), v(c), links, flip, cfg),
            // SAFETY: the caller's.
            None => folded_root_offset_in(v(d2), r2, v(a), v(b), v(c), flip, cfg, || unsafe { self.terms_at(p) }),
        }
    }

    /// Solves the block from the coefficients in the registers `r` and the guesses: the
    /// solution's values are left in their registers.
    #[inline(always)]
    pub(crate) fn run(&self, r: &mut [f64], guess: &[f64], cfg: &NewtonConfig) -> Result<(), BlockFailure> {
        // Every register an operation names is below `needs`, every guess read below `guesses`
        // (checked when the program was built): one test here instead of one per operand.
        assert!(r.len() >= self.needs && guess.len() >= self.guesses, "registers of another model");
        let p = r.as_mut_ptr();
        // SAFETY: every index is below `needs` <= `r.len()`, every guess below `guess.len()`, every
        // run's start one that `runs` returned (made with the program, `runs`).
        unsafe {
            let v = |k: u32| *p.add(k as usize);
            let set = |k: u32, x: f64| *p.add(k as usize) = x;
            let flag = |k: u32| *p.add(k as usize) != 0.0;
            let bit = |b: bool| if b { 1.0 } else { 0.0 };
            for op in &self.ops {
                match *op {
                    Op::Add(d, a, b) => set(d, v(a) + v(b)),
                    Op::Sub(d, a, b) => set(d, v(a) - v(b)),
                    Op::Mul(d, a, b) => set(d, v(a) * v(b)),
                    Op::Div(d, a, b) => set(d, v(a) / v(b)),
                    Op::Neg(d, a) => set(d, -v(a)),
                    Op::Abs(d, a) => set(d, v(a).abs()),
                    Op::Mov(d, a) => set(d, v(a)),
                    // The chain's registers are among the program's, below `needs`.
                    Op::Run(start) => self.runs.run(p, start),
                    Op::Guess(d, u) => set(d, *guess.get_unchecked(u as usize)),
                    Op::CheckGuess(a, b) => check_guess(v(a) + v(b))?,
                    Op::Side { r, right, flip, b, g } => {
                        let red = reduce_turn(v(g));
                        let is_right = red.abs() < FRAC_PI_2;
                        set(r, red);
                        set(right, bit(is_right));
                        set(flip, bit((v(b) > 0.0) == is_right));
                    }
                    Op::FlipZeroA { flip, b, g } => {
                        set(flip, bit((v(b) > 0.0) == (reduce_turn(v(g)).abs() < FRAC_PI_2)));
                    }
                    Op::FlipZeroB { flip, a, g } => set(flip, bit((v(a) > 0.0) == (reduce_turn(v(g)) < 0.0))),
                    Op::FlipSign { flip, a, b, bound, g } => {
                        let (av, bv) = (v(a), v(b));
                        set(flip, bit(sign_at_guess(v(g), 3.0 * v(bound), |(sg, cg)| bv * cg - av * sg) > 0.0));
                    }
                    Op::FlipProduct { flip, a, g } => set(flip, bit((v(a) * reduce_turn(v(g))) < 0.0)),
                    Op::DyadRoots { cq, sq, a, b, c, flip } => {
                        // The magnitude of the equation's terms computed only where the root
                        // fails, as the compiled solve's.
                        let terms = move || self.terms_at(p);
                        let (c0, s0) = dyad_roots_in(v(a), v(b), v(c), flag(flip), cfg, terms)?;
                        set(cq, c0);
                        set(sq, s0);
                    }
                    Op::DyadRootsOf { cq, sq, a, b, c, e0, e1, l0, l1, flip } => {
                        let dyad = [v(a), v(b), v(e0), v(e1), v(l0), v(l1)];
                        let (c0, s0) = dyad_of(dyad, v(c), flag(flip), cfg)?;
                        set(cq, c0);
                        set(sq, s0);
                    }
                    Op::DyadD2 { d, d2, r2, e0, e1, l0, l1 } => {
                        set(d, dyad_d2(v(d2), v(r2), [v(e0), v(e1), v(l0), v(l1)]))
                    }
                    // `folded_root_offset`'s own test first: the coefficients, read only on
                    // its cold path, are not loaded where it passes (the same value).
                    // A dyad's (its `d2` made by `DyadD2`) with the residual of one that
                    // cannot be assembled in its links' lengths: the links looked up on the
                    // cold path, not carried by the operation (a larger `Op` costs every
                    // operation of every step its copy).
                    Op::RootOffset { d, d2: d2_reg, r2, a, b, c, flip } => {
                        let (d2, r2) = (v(d2_reg), v(r2));
                        let offset = if d2 >= 0.0 && (f64::MIN_POSITIVE..=f64::MAX).contains(&r2) {
                            root_offset_deferred(d2, flag(flip))
                        } else {
                            self.off_range(p, [d2_reg, a, b, c], r2, flag(flip), cfg)?
                        };
                        set(d, offset)
                    }
                    Op::PolarNorm { d, r2, e0, e1 } => set(d, polar_norm(v(r2), v(e0), v(e1), cfg)?),
                    Op::PolarSide { s, cq, sq, gs } => {
                        if v(s) * v(gs) < 0.0 {
                            set(s, -v(s));
                            set(cq, -v(cq));
                            set(sq, -v(sq));
                        }
                    }
                    Op::Atan2 { d, s, c } => set(d, v(s).atan2(v(c))),
                    Op::PolarAngle { d, q0, s, gs, g } => {
                        set(d, unwrap_to_turn(half_turn_if(v(q0), v(s) * v(gs) < 0.0), v(g)));
                    }
                    Op::Atan2Unwrap { d, s, c, g } => set(d, unwrap_to_turn(v(s).atan2(v(c)), v(g))),
                    Op::AcosUnwrap { d, c, s, g } => set(d, unwrap_to_turn(acos_on_side(v(c), v(s)), v(g))),
                    Op::AsinNear { d, s, right, r, g } => set(d, asin_near(v(s), flag(right), v(r), v(g))),
                    // Only the values the block has read (three or four of six, mostly).
                    Op::Check { out, len, angles } => {
                        let angles = angles as usize;
                        match len {
                            3 => check_closed(&[v(out[0]), v(out[1]), v(out[2])], angles, cfg)?,
                            4 => check_closed(&[v(out[0]), v(out[1]), v(out[2]), v(out[3])], angles, cfg)?,
                            _ => check_closed(&out.map(v), angles, cfg)?,
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

/// A value while a program is built: a constant of the graph (folded as the emitter folds it)
/// or a register (computed as the emitted expression computes it).
#[derive(Clone, Copy, Debug)]
enum V {
    C(f64),
    R(u32),
}

impl V {
    fn is_zero(self) -> bool {
        matches!(self, V::C(z) if z == 0.0)
    }

    /// The constant, if this is one.
    fn constant(self) -> Option<f64> {
        match self {
            V::C(c) => Some(c),
            V::R(_) => None,
        }
    }
}

/// A program being built.
struct Build<'a> {
    g: &'a Graph,
    extra: &'a mut Extra,
    ops: Vec<Op>,
    /// The registers this program computed whose name is still free to change (see
    /// [`Build::place`]), and what a renamed one became.
    temps: HashMap<u32, Option<u32>>,
    /// Per unknown: the register its guess was loaded into.
    guess_regs: HashMap<usize, u32>,
}

impl Build<'_> {
    /// A coefficient: a constant node as a constant, any other as its register.
    fn v(&self, n: NodeId) -> V {
        match self.g.as_const(n) {
            Some(c) => V::C(c),
            None => V::R(n.0),
        }
    }

    fn m(&self, m: &[[NodeId; 2]; 2]) -> [[V; 2]; 2] {
        [[self.v(m[0][0]), self.v(m[0][1])], [self.v(m[1][0]), self.v(m[1][1])]]
    }

    /// The register of `v` (a constant's, written once).
    fn reg(&mut self, v: V) -> u32 {
        match v {
            V::C(x) => self.extra.constant(x),
            V::R(k) => match self.temps.get(&k) {
                Some(Some(renamed)) => *renamed,
                _ => k,
            },
        }
    }

    /// A new register computed by `make(destination)`.
    fn op(&mut self, make: impl FnOnce(u32) -> Op) -> V {
        let d = self.extra.fresh();
        self.temps.insert(d, None);
        self.ops.push(make(d));
        V::R(d)
    }

    /// `v` as a value the folds no longer see through (the emitter binds it to a local): a
    /// constant becomes its register.
    fn opaque(&mut self, v: V) -> V {
        V::R(self.reg(v))
    }

    fn guess(&mut self, u: usize) -> u32 {
        if let Some(&k) = self.guess_regs.get(&u) {
            return k;
        }
        let k = self.extra.fresh();
        self.ops.push(Op::Guess(k, u as u32));
        self.guess_regs.insert(u, k);
        k
    }

    /// Leaves `v` in register `target` (which nothing else writes) and returns it: the
    /// operation that computed `v` writes there directly when `v` is this program's own
    /// register, otherwise a copy.
    fn place(&mut self, v: V, target: u32) -> u32 {
        if let V::R(k) = v
            && let Some(None) = self.temps.get(&k)
        {
            for op in &mut self.ops {
                for r in op.registers_mut() {
                    if *r == k {
                        *r = target;
                    }
                }
            }
            self.temps.insert(k, Some(target));
            return target;
        }
        let from = self.reg(v);
        if from != target {
            self.ops.push(Op::Mov(target, from));
        }
        target
    }

    fn neg(&mut self, a: V) -> V {
        match a {
            V::C(x) => V::C(-x),
            V::R(_) => {
                let a = self.reg(a);
                self.op(|d| Op::Neg(d, a))
            }
        }
    }

    fn bin(&mut self, a: V, b: V, make: fn(u32, u32, u32) -> Op) -> V {
        let (a, b) = (self.reg(a), self.reg(b));
        self.op(|d| make(d, a, b))
    }

    fn mul(&mut self, a: V, b: V) -> V {
        match (a, b) {
            (V::C(x), V::C(y)) => V::C(x * y),
            _ if a.is_zero() || b.is_zero() => V::C(0.0),
            (V::C(o), e) | (e, V::C(o)) if o == 1.0 => e,
            (V::C(m), e) | (e, V::C(m)) if m == -1.0 => self.neg(e),
            _ => self.bin(a, b, Op::Mul),
        }
    }

    fn add(&mut self, a: V, b: V) -> V {
        match (a, b) {
            (V::C(x), V::C(y)) => V::C(x + y),
            (V::C(0.0), e) | (e, V::C(0.0)) => e,
            _ => self.bin(a, b, Op::Add),
        }
    }

    fn sub(&mut self, a: V, b: V) -> V {
        match (a, b) {
            (V::C(x), V::C(y)) => V::C(x - y),
            (e, V::C(0.0)) => e,
            (V::C(0.0), e) => self.neg(e),
            _ => self.bin(a, b, Op::Sub),
        }
    }

    fn abs(&mut self, a: V) -> V {
        match a {
            V::C(x) => V::C(x.abs()),
            V::R(_) => {
                let a = self.reg(a);
                self.op(|d| Op::Abs(d, a))
            }
        }
    }

    /// `a / b` as the emitted code writes it, never folded afterwards (a constant quotient is
    /// the compiler's constant, the same value).
    fn div(&mut self, a: V, b: V) -> V {
        match (a, b) {
            (V::C(x), V::C(y)) => self.opaque(V::C(x / y)),
            _ => self.bin(a, b, Op::Div),
        }
    }

    /// `a · x` for pairs `(a, x)`, summed from zero as the emitter does.
    fn dot(&mut self, terms: &[(V, V)]) -> V {
        terms.iter().fold(V::C(0.0), |acc, &(a, x)| {
            let ax = self.mul(a, x);
            self.add(acc, ax)
        })
    }

    /// The root `(cos q, sin q)` of `a cos q + b sin q = c` on the side the register `flip`
    /// picks (the emitter's `root`); a dyad's `links` `[e0, e1, l0², l1²]` recompute its `d2`
    /// where `a² + b² - c²` cancels (`dyad_of`, `dyad_d2`).
    fn root(&mut self, a: V, b: V, c: V, flip: u32, links: Option<[V; 4]>) -> (V, V) {
        if let (V::R(_), V::R(_), V::R(_)) = (a, b, c) {
            let (a, b, c) = (self.reg(a), self.reg(b), self.reg(c));
            let (cq, sq) = (self.extra.fresh(), self.extra.fresh());
            self.temps.insert(cq, None);
            self.temps.insert(sq, None);
            match links {
                Some([e0, e1, l0, l1]) => {
                    let (e0, e1, l0, l1) = (self.reg(e0), self.reg(e1), self.reg(l0), self.reg(l1));
                    self.ops.push(Op::DyadRootsOf { cq, sq, a, b, c, e0, e1, l0, l1, flip });
                }
                None => self.ops.push(Op::DyadRoots { cq, sq, a, b, c, flip }),
            }
            return (V::R(cq), V::R(sq));
        }
        let (aa, bb) = (self.mul(a, a), self.mul(b, b));
        let r2 = self.add(aa, bb);
        let cc = self.mul(c, c);
        let d2 = self.sub(r2, cc);
        let d2 = match links {
            Some([e0, e1, l0, l1]) => {
                let (d2, r2) = (self.reg(d2), self.reg(r2));
                let (e0, e1, l0, l1) = (self.reg(e0), self.reg(e1), self.reg(l0), self.reg(l1));
                self.op(|d| Op::DyadD2 { d, d2, r2, e0, e1, l0, l1 })
            }
            None => d2,
        };
        let (d2, r2r, ar, br, cr) = (self.reg(d2), self.reg(r2), self.reg(a), self.reg(b), self.reg(c));
        // In the emitter's order: the value free of the root ahead of it (`root` in
        // `codegen/src/emit/closed_form.rs`). A dyad's `d2` comes from its `DyadD2`, where the
        // run finds its links for the residual of one that cannot be assembled.
        let root_offset = |this: &mut Self| this.op(|d| Op::RootOffset { d, d2, r2: r2r, a: ar, b: br, c: cr, flip });
        let (cq, sq) = if a.is_zero() {
            let ib = self.div(V::C(1.0), b);
            let sq = self.mul(c, ib);
            let d = root_offset(self);
            let dib = self.mul(d, ib);
            (self.neg(dib), sq)
        } else if b.is_zero() {
            let ia = self.div(V::C(1.0), a);
            let cq = self.mul(c, ia);
            let d = root_offset(self);
            (cq, self.mul(d, ia))
        } else {
            let d = root_offset(self);
            let inv = self.div(V::C(1.0), r2);
            let (ac, bd) = (self.mul(a, c), self.mul(b, d));
            let x = self.sub(ac, bd);
            let cq = self.mul(x, inv);
            let (bc, ad) = (self.mul(b, c), self.mul(a, d));
            let y = self.add(bc, ad);
            (cq, self.mul(y, inv))
        };
        (self.opaque(cq), self.opaque(sq))
    }

    /// The sign rule at the guess in register `g` (the emitter's `flip_at_guess`).
    fn flip_at_guess(&mut self, a: V, b: V, g: u32) -> u32 {
        let flip = self.extra.fresh();
        if a.is_zero() {
            let b = self.reg(b);
            self.ops.push(Op::FlipZeroA { flip, b, g });
        } else if b.is_zero() {
            let a = self.reg(a);
            self.ops.push(Op::FlipZeroB { flip, a, g });
        } else {
            let (aa, ab) = (self.abs(a), self.abs(b));
            let bound = self.add(aa, ab);
            let (a, b, bound) = (self.reg(a), self.reg(b), self.reg(bound));
            self.ops.push(Op::FlipSign { flip, a, b, bound, g });
        }
        flip
    }

    fn angle_equation(&mut self, a: V, b: V, c: V, u: usize) -> [V; 3] {
        let g = self.guess(u);
        if a.is_zero() {
            let (r, right, flip) = (self.extra.fresh(), self.extra.fresh(), self.extra.fresh());
            let breg = self.reg(b);
            self.ops.push(Op::Side { r, right, flip, b: breg, g });
            let (cq, sq) = self.root(a, b, c, flip, None);
            let s = self.reg(sq);
            let q = self.op(|d| Op::AsinNear { d, s, right, r, g });
            return [q, cq, sq];
        }
        let flip = self.flip_at_guess(a, b, g);
        let (cq, sq) = self.root(a, b, c, flip, None);
        let (c, s) = (self.reg(cq), self.reg(sq));
        let q = if b.is_zero() {
            self.op(|d| Op::AcosUnwrap { d, c, s, g })
        } else {
            self.op(|d| Op::Atan2Unwrap { d, s, c, g })
        };
        [q, cq, sq]
    }

    /// The dyad; its cosine and sine of the first angle are placed in their `targets` as soon
    /// as they are known.
    fn dyad(
        &mut self,
        a: &[[V; 2]; 2],
        b: &[[V; 2]; 2],
        reflect: [bool; 2],
        e: [V; 2],
        angles: [usize; 2],
        targets: &[u32],
    ) -> [V; 6] {
        let (g0, g1) = (self.guess(angles[0]), self.guess(angles[1]));
        let mut k = |i: usize, j: usize| {
            let (x, y) = (self.mul(a[0][i], b[1][j]), self.mul(a[1][i], b[0][j]));
            self.sub(x, y)
        };
        let (k00, k01) = (k(0, 0), k(0, 1));
        let sigma =
            if reflect[0] == reflect[1] { self.op(|d| Op::Sub(d, g1, g0)) } else { self.op(|d| Op::Add(d, g1, g0)) };
        let sigma = self.reg(sigma);
        let (ca, cb) = if reflect[0] { (self.neg(k01), k00) } else { (k01, self.neg(k00)) };
        let flip = if cb.is_zero() {
            let flip = self.extra.fresh();
            let a = self.reg(ca);
            self.ops.push(Op::FlipProduct { flip, a, g: sigma });
            flip
        } else {
            self.flip_at_guess(ca, cb, sigma)
        };
        let ca = self.dot(&[(a[0][0], e[0]), (a[1][0], e[1])]);
        let cb = self.dot(&[(a[0][1], e[0]), (a[1][1], e[1])]);
        let l0 = self.dot(&[(a[0][0], a[0][0]), (a[1][0], a[1][0])]);
        let l1 = self.dot(&[(b[0][0], b[0][0]), (b[1][0], b[1][0])]);
        let ee = self.dot(&[(e[0], e[0]), (e[1], e[1])]);
        let l1l0 = self.sub(l1, l0);
        let x = self.sub(l1l0, ee);
        let cc = self.mul(V::C(0.5), x);
        let (cq, sq) = self.root(ca, cb, cc, flip, Some([e[0], e[1], l0, l1]));
        let (cq, sq) = (V::R(self.place(cq, targets[2])), V::R(self.place(sq, targets[3])));
        let dx = self.dot(&[(a[0][0], cq), (a[0][1], sq)]);
        let vx = self.add(e[0], dx);
        let dy = self.dot(&[(a[1][0], cq), (a[1][1], sq)]);
        let vy = self.add(e[1], dy);
        let il1 = self.div(V::C(-1.0), l1);
        let c1 = self.dot(&[(b[0][0], vx), (b[1][0], vy)]);
        let c1 = self.mul(c1, il1);
        let s1 = self.dot(&[(b[0][1], vx), (b[1][1], vy)]);
        let s1 = self.mul(s1, il1);
        let (c1, s1) = (V::R(self.place(c1, targets[4])), V::R(self.place(s1, targets[5])));
        let (c, s, c1r, s1r) = (self.reg(cq), self.reg(sq), self.reg(c1), self.reg(s1));
        let q0 = self.op(|d| Op::Atan2Unwrap { d, s, c, g: g0 });
        let q1 = self.op(|d| Op::Atan2Unwrap { d, s: s1r, c: c1r, g: g1 });
        [q0, q1, cq, sq, c1, s1]
    }

    /// The polar length; its length, cosine and sine are placed in their `targets` before the
    /// half turn that may negate them in place.
    fn polar(&mut self, w: &[[V; 2]; 2], e: [V; 2], u: usize, length: usize, targets: &[u32]) -> [V; 4] {
        let (g, gs) = (self.guess(u), self.guess(length));
        let (x, y) = (self.mul(w[0][0], e[1]), self.mul(w[1][0], e[0]));
        let a = self.sub(x, y);
        let (x, y) = (self.mul(w[0][1], e[1]), self.mul(w[1][1], e[0]));
        let b = self.sub(x, y);
        let (aa, bb) = (self.mul(a, a), self.mul(b, b));
        let r2 = self.add(aa, bb);
        // The angle from the unnormalised direction `(-a, b)`, as the emitted code takes it (it
        // need not wait for the normalisation); a half turn below when the length flips it.
        let na = self.neg(a);
        let (na, br) = (self.reg(na), self.reg(b));
        let q0 = self.op(|d| Op::Atan2 { d, s: na, c: br });
        let (r2, e0, e1) = (self.reg(r2), self.reg(e[0]), self.reg(e[1]));
        let ir = self.op(|d| Op::PolarNorm { d, r2, e0, e1 });
        let c0 = self.mul(b, ir);
        let s0 = self.mul(a, ir);
        let s0 = self.neg(s0);
        let cq = V::R(self.place(c0, targets[2]));
        let sq = V::R(self.place(s0, targets[3]));
        let w0 = self.dot(&[(w[0][0], cq), (w[0][1], sq)]);
        let w1 = self.dot(&[(w[1][0], cq), (w[1][1], sq)]);
        let num = self.dot(&[(w0, e[0]), (w1, e[1])]);
        let s = match constant_norm2(w.map(|r| r.map(V::constant))) {
            Some(1.0) => self.neg(num),
            Some(k2) => {
                let n = self.neg(num);
                self.div(n, V::C(k2))
            }
            None => {
                let den = self.dot(&[(w0, w0), (w1, w1)]);
                let n = self.neg(num);
                self.div(n, den)
            }
        };
        let s = self.place(s, targets[1]);
        let (c, sr) = (targets[2], targets[3]);
        let q0 = self.reg(q0);
        let q = self.op(|d| Op::PolarAngle { d, q0, s, gs, g });
        self.ops.push(Op::PolarSide { s, cq: c, sq: sr, gs });
        [q, V::R(s), cq, sq]
    }

    fn angle_slider(&mut self, m: &[[V; 2]; 2], d: [V; 2], e: [V; 2], u: usize) -> [V; 4] {
        let g = self.guess(u);
        let (x, y) = (self.mul(d[1], m[0][0]), self.mul(d[0], m[1][0]));
        let a = self.sub(x, y);
        let (x, y) = (self.mul(d[1], m[0][1]), self.mul(d[0], m[1][1]));
        let b = self.sub(x, y);
        let (x, y) = (self.mul(d[0], e[1]), self.mul(d[1], e[0]));
        let c = self.sub(x, y);
        let flip = self.flip_at_guess(a, b, g);
        let (cq, sq) = self.root(a, b, c, flip, None);
        let t = self.dot(&[(m[0][0], cq), (m[0][1], sq)]);
        let r0 = self.add(t, e[0]);
        let t = self.dot(&[(m[1][0], cq), (m[1][1], sq)]);
        let r1 = self.add(t, e[1]);
        let num = self.dot(&[(d[0], r0), (d[1], r1)]);
        let den = self.dot(&[(d[0], d[0]), (d[1], d[1])]);
        let (c, s) = (self.reg(cq), self.reg(sq));
        let q = self.op(|d| Op::Atan2Unwrap { d, s, c, g });
        let n = self.neg(num);
        let s = self.div(n, den);
        [q, s, cq, sq]
    }
}
