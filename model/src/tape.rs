//! The instruction tape: the plan's expression graph as straight-line instructions over `f64`
//! registers, one register per graph node.
//!
//! A register holds its node's value: constants are written once when the tape is built,
//! parameters when they are set, inputs, unknowns and analogs when a step reaches them, every
//! other node by the instruction that computes it. The instructions of one part of a step (a
//! block's coefficients, its Newton evaluation, its analogs' right-hand sides, the outputs) form
//! a [`Segment`]: the nodes its roots need that no earlier segment computed, in the graph's
//! order (a topological order). Each instruction performs the operation the emitted code
//! writes for its node (`a * a` for a square, `1.0 / a` for a reciprocal, `f64::signum`, ...),
//! so that a run-time step computes the same values as the compiled one.
//!
//! What makes a step cheaper without changing a value: the nodes of the parameters alone are
//! computed when the parameters are set ([`statics`]; the compiled step recomputes them with
//! the same operations), a sine and a cosine of one argument are one instruction, up to four
//! consecutive arithmetic operations share one dispatch (each still rounds on its own, in its
//! order: no fused multiply-add, which the emitted code does not use), and each step jumps to
//! the next one's function ([`Step`]: threaded code, no loop between two steps). Operands are
//! `u32` register indices checked once per segment when it is built.
//!
//! A Newton block's evaluation segment ([`Builder::near_segment`]) computes each sine and cosine
//! of one argument by a rotation slot of its own ([`Ins::NearSinCos`], `crate::near`), as the
//! emitted evaluation asks its `NearTrig`: every other segment calls libm, as the emitted
//! straight-line code does.

use crate::extra::Extra;
use crate::near::NearSlots;
use kinloop_codegen::graph::angle_sums::{AngleSum, angle_sum, sources};
use kinloop_codegen::graph::dag::{Func, Graph, Leaf, NodeId, Op};
use std::collections::HashSet;

/// One operation: destination register first, then the operands' registers.
///
/// The elementary functions are variants of their own, and a sine and a cosine of one argument
/// are one instruction ([`Ins::SinCos`], as the emitted code's `sin_cos`, which computes
/// `(sin, cos)`). A segment executes them as [`Step`]s.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Ins {
    Add(u32, u32, u32),
    Sub(u32, u32, u32),
    Mul(u32, u32, u32),
    Div(u32, u32, u32),
    Neg(u32, u32),
    /// `a * a` (the emitter's square).
    Square(u32, u32),
    /// `1.0 / a` (the emitter's reciprocal).
    Recip(u32, u32),
    Powi(u32, u32, i32),
    Powf(u32, u32, u32),
    Sin(u32, u32),
    Cos(u32, u32),
    /// `(sin a, cos a)` into the first two registers.
    SinCos(u32, u32, u32),
    /// `sin(a + b)` from `sin a`, `cos a`, `sin b`, `cos b` (`d, sin_a, cos_a, sin_b,
    /// cos_b`): by angle addition, the emitted code's `add_angles` (see
    /// `kinloop_codegen::graph::angle_sums`).
    SinSum(u32, [u32; 4]),
    /// `cos(a + b)` as [`Ins::SinSum`].
    CosSum(u32, [u32; 4]),
    /// `(sin(a + b), cos(a + b))` into the first two registers, from `sin a`, `cos a`, `sin b`,
    /// `cos b`.
    SinCosSum(u32, u32, [u32; 4]),
    /// `(sin a, cos a)` into the first two registers by a Newton block's rotation slot, whose
    /// [`WIDTH`](crate::near::WIDTH) registers start at the fourth (`crate::near`: rotated from
    /// the slot's previous argument, as the emitted block's `NearTrig`).
    NearSinCos(u32, u32, u32, u32),
    Tan(u32, u32),
    Asin(u32, u32),
    Acos(u32, u32),
    Atan(u32, u32),
    Sqrt(u32, u32),
    Exp(u32, u32),
    Ln(u32, u32),
    Abs(u32, u32),
    Signum(u32, u32),
    Floor(u32, u32),
    Atan2(u32, u32, u32),
    /// `select(a, b, x, y)` (`graph::dag::select`: `min`, `max`, `clamp` and their derivatives),
    /// as `d, a, b, x, y`.
    Select(u32, u32, u32, u32, u32),
}

impl Ins {
    /// The registers the instruction writes, then those it reads (of a rotation slot's, the
    /// last: the registers a run needs are counted from the largest).
    fn registers(&self) -> impl Iterator<Item = u32> {
        let (v, n): ([u32; 6], usize) = match *self {
            Ins::SinCosSum(s, c, [sa, ca, sb, cb]) => ([s, c, sa, ca, sb, cb], 6),
            Ins::Select(d, a, b, x, y) | Ins::SinSum(d, [a, b, x, y]) | Ins::CosSum(d, [a, b, x, y]) => {
                ([d, a, b, x, y, 0], 5)
            }
            Ins::NearSinCos(s, c, a, st) => ([s, c, a, st + crate::near::WIDTH as u32 - 1, 0, 0], 4),
            Ins::Add(d, a, b)
            | Ins::Sub(d, a, b)
            | Ins::Mul(d, a, b)
            | Ins::Div(d, a, b)
            | Ins::Powf(d, a, b)
            | Ins::Atan2(d, a, b)
            | Ins::SinCos(d, a, b) => ([d, a, b, 0, 0, 0], 3),
            Ins::Neg(d, a)
            | Ins::Square(d, a)
            | Ins::Recip(d, a)
            | Ins::Powi(d, a, _)
            | Ins::Sin(d, a)
            | Ins::Cos(d, a)
            | Ins::Tan(d, a)
            | Ins::Asin(d, a)
            | Ins::Acos(d, a)
            | Ins::Atan(d, a)
            | Ins::Sqrt(d, a)
            | Ins::Exp(d, a)
            | Ins::Ln(d, a)
            | Ins::Abs(d, a)
            | Ins::Signum(d, a)
            | Ins::Floor(d, a) => ([d, a, 0, 0, 0, 0], 2),
        };
        v.into_iter().take(n)
    }

    /// The arithmetic operation `(code, [d, a, b])` of the instruction ([`ADD`], ... [`NEG`],
    /// whose `b` is its `a`), for grouping.
    fn arith(&self) -> Option<(u8, [u32; 3])> {
        match *self {
            Ins::Add(d, a, b) => Some((ADD, [d, a, b])),
            Ins::Sub(d, a, b) => Some((SUB, [d, a, b])),
            Ins::Mul(d, a, b) => Some((MUL, [d, a, b])),
            Ins::Div(d, a, b) => Some((DIV, [d, a, b])),
            Ins::Neg(d, a) => Some((NEG, [d, a, a])),
            _ => None,
        }
    }

    /// The step executing this instruction alone.
    fn step(self) -> Step {
        let f = |exec: Exec, r: &[u32]| {
            let mut regs = [0; 12];
            regs[..r.len()].copy_from_slice(r);
            Step { exec, r: regs }
        };
        match self {
            // `group` makes the steps of every arithmetic instruction.
            Ins::Add(..) | Ins::Sub(..) | Ins::Mul(..) | Ins::Div(..) | Ins::Neg(..) => {
                unreachable!("an arithmetic instruction is grouped")
            }
            Ins::Square(d, a) => f(square, &[d, a]),
            Ins::Recip(d, a) => f(recip, &[d, a]),
            // The exponent's bits in the operand's place.
            Ins::Powi(d, a, k) => f(powi, &[d, a, k as u32]),
            Ins::Powf(d, a, b) => f(powf, &[d, a, b]),
            Ins::Sin(d, a) => f(unary::<SIN>, &[d, a]),
            Ins::Cos(d, a) => f(unary::<COS>, &[d, a]),
            Ins::SinCos(s, c, a) => f(sin_cos_step, &[s, c, a]),
            Ins::SinSum(d, [sa, ca, sb, cb]) => f(sum_part_step::<0>, &[d, sa, ca, sb, cb]),
            Ins::CosSum(d, [sa, ca, sb, cb]) => f(sum_part_step::<1>, &[d, sa, ca, sb, cb]),
            Ins::SinCosSum(s, c, [sa, ca, sb, cb]) => f(sin_cos_sum_step, &[s, c, sa, ca, sb, cb]),
            Ins::NearSinCos(s, c, a, st) => f(near_sin_cos_step, &[s, c, a, st]),
            Ins::Tan(d, a) => f(unary::<TAN>, &[d, a]),
            Ins::Asin(d, a) => f(unary::<ASIN>, &[d, a]),
            Ins::Acos(d, a) => f(unary::<ACOS>, &[d, a]),
            Ins::Atan(d, a) => f(unary::<ATAN>, &[d, a]),
            Ins::Sqrt(d, a) => f(unary::<SQRT>, &[d, a]),
            Ins::Exp(d, a) => f(unary::<EXP>, &[d, a]),
            Ins::Ln(d, a) => f(unary::<LN>, &[d, a]),
            Ins::Abs(d, a) => f(unary::<ABS>, &[d, a]),
            Ins::Signum(d, a) => f(unary::<SIGNUM>, &[d, a]),
            Ins::Floor(d, a) => f(unary::<FLOOR>, &[d, a]),
            Ins::Atan2(d, y, x) => f(atan2, &[d, y, x]),
            Ins::Select(d, a, b, x, y) => f(select, &[d, a, b, x, y]),
        }
    }
}

/// What a step executes: a function of the registers (`p`, at least the segment's `needs` of
/// them) and of the step itself (`s`, whose registers it reads), which then executes the next
/// step (see [`next`]).
///
/// # Safety
/// `p` holds every register the steps from `s` to the next [`ret`] name, and a [`ret`] follows
/// `s` in its array.
type Exec = unsafe fn(p: *mut f64, s: *const Step);

/// One dispatch of a segment: up to four consecutive arithmetic instructions, or one other.
///
/// A step's function performs it and then calls the next step's function (threaded code: the
/// call is in tail position with the same arguments, which the optimiser compiles to a jump,
/// two instructions a dispatch instead of a loop's seven); a segment's steps form chains of at
/// most [`CHAIN`] steps ended by [`ret`], so that without that optimisation (a debug build) the
/// calls nest at most [`CHAIN`] deep. The grouped arithmetic instructions are one function each
/// (`arith3::<MUL, MUL, ADD>`, ...) that performs the operations one after the other, each
/// rounded on its own and stored to its register before the next reads the registers (no fused
/// multiply-add, no reordering): the values are those of the separate operations.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Step {
    exec: Exec,
    /// The registers, as the function reads them (`[d, a, b]` per arithmetic operation).
    r: [u32; 12],
}

/// The arithmetic operations' codes (a const parameter of the grouped steps' functions).
const ADD: u8 = 0;
const SUB: u8 = 1;
const MUL: u8 = 2;
const DIV: u8 = 3;
/// `-a` (its `b` is its `a`: loaded, unused).
const NEG: u8 = 4;

/// The steps of a chain (a [`ret`] after them).
const CHAIN: usize = 32;

/// Executes the step after `s`.
///
/// # Safety
/// As [`Exec`]: `s` is not a [`ret`].
#[inline(always)]
unsafe fn next(p: *mut f64, s: *const Step) {
    // SAFETY: a `ret` ends every chain, so the step after a step that is not one exists.
    unsafe {
        let n = s.add(1);
        ((*n).exec)(p, n)
    }
}

/// The end of a chain.
///
/// # Safety
/// None needed (it reads nothing), an [`Exec`] for its type.
unsafe fn ret(_: *mut f64, _: *const Step) {}

/// The registers of a chain's end, which [`ret`] does not read: an index no register has, so
/// that an end is told from a step by its registers (function pointers are no test: the
/// compiler may merge functions of the same code, or give one function an address in each
/// codegen unit).
const END: [u32; 12] = [u32::MAX; 12];

/// The operation `K` on `a` and `b`, as the emitted code writes it.
#[inline(always)]
fn op<const K: u8>(a: f64, b: f64) -> f64 {
    match K {
        ADD => a + b,
        SUB => a - b,
        MUL => a * b,
        DIV => a / b,
        _ => -a,
    }
}

/// `r[d] = K(r[a], r[b])`.
///
/// # Safety
/// `d`, `a`, `b` below the number of registers at `p`.
#[inline(always)]
unsafe fn arith<const K: u8>(p: *mut f64, d: u32, a: u32, b: u32) {
    // SAFETY: the caller's.
    unsafe { *p.add(d as usize) = op::<K>(*p.add(a as usize), *p.add(b as usize)) }
}

/// One arithmetic operation.
///
/// # Safety
/// Every register index of `r` below the number of registers at `p` (as for every [`Exec`]).
unsafe fn arith1<const F: u8>(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        arith::<F>(p, r[0], r[1], r[2]);
        next(p, s)
    }
}

/// Two arithmetic operations, in order.
///
/// # Safety
/// As [`arith1`].
unsafe fn arith2<const F: u8, const G: u8>(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        arith::<F>(p, r[0], r[1], r[2]);
        arith::<G>(p, r[3], r[4], r[5]);
        next(p, s)
    }
}

/// Three arithmetic operations, in order.
///
/// # Safety
/// As [`arith1`].
unsafe fn arith3<const F: u8, const G: u8, const H: u8>(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        arith::<F>(p, r[0], r[1], r[2]);
        arith::<G>(p, r[3], r[4], r[5]);
        arith::<H>(p, r[6], r[7], r[8]);
        next(p, s)
    }
}

/// Four arithmetic operations, in order.
///
/// # Safety
/// As [`arith1`].
unsafe fn arith4<const F: u8, const G: u8, const H: u8, const I: u8>(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        arith::<F>(p, r[0], r[1], r[2]);
        arith::<G>(p, r[3], r[4], r[5]);
        arith::<H>(p, r[6], r[7], r[8]);
        arith::<I>(p, r[9], r[10], r[11]);
        next(p, s)
    }
}

/// The functions of one, two, three and four arithmetic operations, by their codes.
macro_rules! by_code {
    ($f:ident; $($k:literal),*) => {
        [$f::<$($k,)* 0> as Exec, $f::<$($k,)* 1>, $f::<$($k,)* 2>, $f::<$($k,)* 3>, $f::<$($k,)* 4>]
    };
}
macro_rules! by_codes {
    ($f:ident; $($k:literal),*) => {
        [by_code!($f; $($k,)* 0), by_code!($f; $($k,)* 1), by_code!($f; $($k,)* 2), by_code!($f; $($k,)* 3), by_code!($f; $($k,)* 4)]
    };
}
const ARITH1: [Exec; 5] = by_code!(arith1;);
const ARITH2: [[Exec; 5]; 5] = by_codes!(arith2;);
macro_rules! by_codes3 {
    ($f:ident; $($k:literal),*) => {
        [by_codes!($f; $($k,)* 0), by_codes!($f; $($k,)* 1), by_codes!($f; $($k,)* 2), by_codes!($f; $($k,)* 3), by_codes!($f; $($k,)* 4)]
    };
}
const ARITH3: [[[Exec; 5]; 5]; 5] = by_codes3!(arith3;);
const ARITH4: [[[[Exec; 5]; 5]; 5]; 5] =
    [by_codes3!(arith4; 0), by_codes3!(arith4; 1), by_codes3!(arith4; 2), by_codes3!(arith4; 3), by_codes3!(arith4; 4)];

/// The elementary functions' codes (a const parameter of [`unary`]).
const SIN: u8 = 0;
const COS: u8 = 1;
const TAN: u8 = 2;
const ASIN: u8 = 3;
const ACOS: u8 = 4;
const ATAN: u8 = 5;
const SQRT: u8 = 6;
const EXP: u8 = 7;
const LN: u8 = 8;
const ABS: u8 = 9;
const SIGNUM: u8 = 10;
const FLOOR: u8 = 11;

/// `r[d] = F(r[a])`.
///
/// # Safety
/// As [`arith1`].
unsafe fn unary<const F: u8>(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        let x = *p.add(r[1] as usize);
        *p.add(r[0] as usize) = match F {
            SIN => x.sin(),
            COS => x.cos(),
            TAN => x.tan(),
            ASIN => x.asin(),
            ACOS => x.acos(),
            ATAN => x.atan(),
            SQRT => x.sqrt(),
            EXP => x.exp(),
            LN => x.ln(),
            ABS => x.abs(),
            FLOOR => x.floor(),
            // `f64::signum`, as the emitted code calls it (not the constant folder's, which
            // gives 0 at 0).
            _ => x.signum(),
        };
        next(p, s)
    }
}

/// `r[d] = r[a] * r[a]` (the emitter's square).
///
/// # Safety
/// As [`arith1`].
unsafe fn square(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        let x = *p.add(r[1] as usize);
        *p.add(r[0] as usize) = x * x;
        next(p, s)
    }
}

/// `r[d] = 1.0 / r[a]` (the emitter's reciprocal).
///
/// # Safety
/// As [`arith1`].
unsafe fn recip(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        *p.add(r[0] as usize) = 1.0 / *p.add(r[1] as usize);
        next(p, s)
    }
}

/// `r[d] = r[a].powi(k)`, the exponent's bits in `r[2]`.
///
/// # Safety
/// As [`arith1`] (`r[2]` is not a register).
unsafe fn powi(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        *p.add(r[0] as usize) = (*p.add(r[1] as usize)).powi(r[2] as i32);
        next(p, s)
    }
}

/// `r[d] = r[a].powf(r[b])`.
///
/// # Safety
/// As [`arith1`].
unsafe fn powf(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        *p.add(r[0] as usize) = (*p.add(r[1] as usize)).powf(*p.add(r[2] as usize));
        next(p, s)
    }
}

/// `r[d] = r[y].atan2(r[x])`.
///
/// # Safety
/// As [`arith1`].
unsafe fn atan2(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        *p.add(r[0] as usize) = (*p.add(r[1] as usize)).atan2(*p.add(r[2] as usize));
        next(p, s)
    }
}

/// `r[d] = select(r[a], r[b], r[x], r[y])` (the emitted code's comparisons).
///
/// # Safety
/// As [`arith1`].
unsafe fn select(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        let v = |k: usize| *p.add(r[k] as usize);
        *p.add(r[0] as usize) = kinloop_codegen::graph::dag::select(v(1), v(2), v(3), v(4));
        next(p, s)
    }
}

/// `(r[s], r[c]) = r[a].sin_cos()`.
///
/// # Safety
/// As [`arith1`].
unsafe fn sin_cos_step(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        let (sin, cos) = (*p.add(r[2] as usize)).sin_cos();
        *p.add(r[0] as usize) = sin;
        *p.add(r[1] as usize) = cos;
        next(p, s)
    }
}

/// `r[d]` = part `K` (0 the sine, 1 the cosine) of `add_angles((r[sa], r[ca]), (r[sb], r[cb]))`.
///
/// # Safety
/// As [`arith1`].
unsafe fn sum_part_step<const K: usize>(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        let v = |k: usize| *p.add(r[k] as usize);
        let (sin, cos) = kinloop_runtime::generated::add_angles((v(1), v(2)), (v(3), v(4)));
        *p.add(r[0] as usize) = if K == 0 { sin } else { cos };
        next(p, s)
    }
}

/// `(r[s], r[c]) = add_angles((r[sa], r[ca]), (r[sb], r[cb]))`: the sine and cosine of a sum
/// of angles by angle addition, as the emitted code computes them.
///
/// # Safety
/// As [`arith1`].
unsafe fn sin_cos_sum_step(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        let v = |k: usize| *p.add(r[k] as usize);
        let (sin, cos) = kinloop_runtime::generated::add_angles((v(2), v(3)), (v(4), v(5)));
        *p.add(r[0] as usize) = sin;
        *p.add(r[1] as usize) = cos;
        next(p, s)
    }
}

/// `(r[s], r[c]) = (sin r[a], cos r[a])` by the rotation slot in the registers from `r[3]` on
/// (`crate::near::sin_cos`).
///
/// # Safety
/// As [`arith1`] (the slot's registers too: counted in `needs` by [`Ins::registers`]).
unsafe fn near_sin_cos_step(p: *mut f64, s: *const Step) {
    // SAFETY: the caller's.
    unsafe {
        let r = &(*s).r;
        let (sin, cos) = crate::near::sin_cos(p.add(r[3] as usize), *p.add(r[2] as usize));
        *p.add(r[0] as usize) = sin;
        *p.add(r[1] as usize) = cos;
        next(p, s)
    }
}

/// A run of instructions, executed in order.
#[derive(Clone, Debug, Default)]
pub(crate) struct Segment {
    steps: Vec<Step>,
    /// One more than the largest register an instruction names: the registers a run needs.
    needs: usize,
    /// The graph operations the segment performs (a step may perform four).
    ops: usize,
}

impl Segment {
    /// Executes the segment over the registers.
    #[inline]
    pub(crate) fn run(&self, r: &mut [f64]) {
        if self.steps.is_empty() {
            return;
        }
        // Every register a step names is below `needs` (checked when the segment was built):
        // one test here instead of one per operand.
        assert!(r.len() >= self.needs, "registers of another tape");
        // SAFETY: `r` holds at least `needs` registers.
        unsafe { self.run_raw(r.as_mut_ptr()) }
    }

    /// Executes the segment over the registers at `p`.
    ///
    /// # Safety
    /// `p` points to at least `needs` registers.
    #[inline]
    unsafe fn run_raw(&self, p: *mut f64) {
        // The chains start every `CHAIN + 1` steps (see `Segment::of`); past the last one the
        // pointer may leave the array (`wrapping_add`: only compared, never read).
        let (mut chain, end) = (self.steps.as_ptr(), self.steps.as_ptr_range().end);
        while chain < end {
            // SAFETY: every register index of a step is below `needs` (see `Segment::of`), the
            // caller's `p` holds `needs` registers, and every chain ends with a `ret`.
            unsafe { ((*chain).exec)(p, chain) };
            chain = chain.wrapping_add(CHAIN + 1);
        }
    }

    /// A segment of `ins` (one instruction per graph operation, in order): a sine and a cosine
    /// of one argument merged, consecutive arithmetic operations grouped by four, the
    /// registers counted.
    fn new(ins: Vec<Ins>) -> Segment {
        Segment::of(sin_cos(ins))
    }

    /// A segment executing `ins` in order, consecutive arithmetic operations grouped by four.
    fn of(ins: Vec<Ins>) -> Segment {
        let ops = ins
            .iter()
            .map(|i| if matches!(i, Ins::SinCos(..) | Ins::NearSinCos(..) | Ins::SinCosSum(..)) { 2 } else { 1 })
            .sum();
        let needs = ins.iter().flat_map(Ins::registers).max().map_or(0, |m| m as usize + 1);
        // Chains of `CHAIN` steps, each followed by a `ret` (the last one shorter).
        let mut steps = Vec::new();
        for chain in group(&ins).chunks(CHAIN) {
            steps.extend_from_slice(chain);
            steps.push(Step { exec: ret, r: END });
        }
        Segment { steps, needs, ops }
    }

    /// The number of graph operations.
    pub(crate) fn len(&self) -> usize {
        self.ops
    }

    /// One more than the largest register the segment names: the registers a run needs.
    pub(crate) fn needs(&self) -> usize {
        self.needs
    }
}

/// Chains of steps in one array, each entered by where it starts: the arithmetic of a closed
/// form's program, entered from its operations without a segment's bookkeeping.
#[derive(Clone, Debug, Default)]
pub(crate) struct Chains {
    steps: Vec<Step>,
    /// One more than the largest register a step names.
    needs: usize,
}

impl Chains {
    /// Appends the steps of `ins` (in order, grouped as a segment's) and returns where each of
    /// their chains starts: executing the chains in that order executes `ins`.
    pub(crate) fn push(&mut self, ins: &[Ins]) -> Vec<u32> {
        let regs = ins.iter().flat_map(Ins::registers).max().map_or(0, |m| m as usize + 1);
        self.needs = self.needs.max(regs);
        let mut starts = Vec::new();
        for chain in group(ins).chunks(CHAIN) {
            starts.push(self.steps.len() as u32);
            self.steps.extend_from_slice(chain);
            self.steps.push(Step { exec: ret, r: END });
        }
        starts
    }

    /// One more than the largest register a step names: the registers a run needs.
    pub(crate) fn needs(&self) -> usize {
        self.needs
    }

    /// Executes the chain starting at `start`.
    ///
    /// # Safety
    /// `start` is one that [`Chains::push`] returned, and `p` points to at least
    /// [`Chains::needs`] registers.
    #[inline]
    pub(crate) unsafe fn run(&self, p: *mut f64, start: u32) {
        debug_assert!((start as usize) < self.steps.len(), "a start that `push` returned");
        // SAFETY: the caller's; the chain ends with a `ret` (see `Chains::push`).
        unsafe {
            let s = self.steps.as_ptr().add(start as usize);
            ((*s).exec)(p, s)
        }
    }
}

/// Merges a sine and a cosine of the same register into one [`Ins::SinCos`] at the place of
/// the first: its argument is computed before either, and nothing between the two reads the
/// second's register (it is written once, by the second).
fn sin_cos(ins: Vec<Ins>) -> Vec<Ins> {
    let mut out: Vec<Ins> = Vec::with_capacity(ins.len());
    // Per argument register: the index in `out` of a lone sine or cosine of it.
    let mut lone: std::collections::HashMap<u32, usize> = std::collections::HashMap::new();
    // Per sum (the registers of `sin a`, `cos a`, `sin b`, `cos b`): the index in `out` of a
    // lone sine or cosine of it.
    let mut lone_sum: std::collections::HashMap<[u32; 4], usize> = std::collections::HashMap::new();
    for i in ins {
        match i {
            Ins::SinSum(_, parts) | Ins::CosSum(_, parts) => {
                if let Some(k) = lone_sum.remove(&parts) {
                    match (out[k], i) {
                        (Ins::SinSum(s, _), Ins::CosSum(c, _)) | (Ins::CosSum(c, _), Ins::SinSum(s, _)) => {
                            out[k] = Ins::SinCosSum(s, c, parts);
                            continue;
                        }
                        _ => {}
                    }
                }
                lone_sum.insert(parts, out.len());
                out.push(i);
            }
            Ins::Sin(_, a) | Ins::Cos(_, a) => {
                if let Some(k) = lone.remove(&a) {
                    match (out[k], i) {
                        (Ins::Sin(s, _), Ins::Cos(c, _)) | (Ins::Cos(c, _), Ins::Sin(s, _)) => {
                            out[k] = Ins::SinCos(s, c, a);
                            continue;
                        }
                        _ => {}
                    }
                }
                lone.insert(a, out.len());
                out.push(i);
            }
            _ => out.push(i),
        }
    }
    out
}

/// The steps of `ins`: each run of consecutive arithmetic instructions in steps of four (the
/// last of a run three, two or one), every other instruction a step of its own.
fn group(ins: &[Ins]) -> Vec<Step> {
    let mut out = Vec::with_capacity(ins.len());
    let mut k = 0;
    while k < ins.len() {
        let run: Vec<(u8, [u32; 3])> = ins[k..].iter().map_while(Ins::arith).take(4).collect();
        let step = match run[..] {
            [] => ins[k].step(),
            [(f, a)] => Step { exec: ARITH1[f as usize], r: regs(&[a]) },
            [(f, a), (g, b)] => Step { exec: ARITH2[f as usize][g as usize], r: regs(&[a, b]) },
            [(f, a), (g, b), (h, c)] => Step { exec: ARITH3[f as usize][g as usize][h as usize], r: regs(&[a, b, c]) },
            [(f, a), (g, b), (h, c), (i, d), ..] => {
                Step { exec: ARITH4[f as usize][g as usize][h as usize][i as usize], r: regs(&[a, b, c, d]) }
            }
        };
        k += run.len().max(1);
        out.push(step);
    }
    out
}

/// The registers of a step's arithmetic operations, in order.
fn regs(ops: &[[u32; 3]]) -> [u32; 12] {
    let mut r = [0; 12];
    for (k, o) in ops.iter().enumerate() {
        r[3 * k..3 * k + 3].copy_from_slice(o);
    }
    r
}

/// Builds segments in the order a step runs them, each computing only what no earlier one did.
pub(crate) struct Builder<'g> {
    g: &'g Graph,
    /// Per node: whether a register already holds its value when the next segment runs.
    known: Vec<bool>,
}

/// A node the segments need whose value nothing provides: a leaf read before its stage (a
/// plan the tape does not understand). Never expected from the macro's planner.
#[derive(Debug)]
pub(crate) struct Unavailable(pub(crate) Leaf);

impl<'g> Builder<'g> {
    /// A builder over `g`, with the constants, parameters, inputs and the nodes of parameters
    /// alone (computed when the parameters are set, [`statics`]) known.
    pub(crate) fn new(g: &'g Graph) -> Self {
        let mut known = fixed(g);
        for (k, op) in (0..g.len()).map(|k| (k, g.op(NodeId(k as u32)))) {
            known[k] |= matches!(op, Op::Leaf(Leaf::Input(_)));
        }
        Builder { g, known }
    }

    /// Marks nodes whose registers a solve writes (unknowns, analogs, a closed form's sines and
    /// cosines).
    pub(crate) fn provide(&mut self, nodes: impl IntoIterator<Item = NodeId>) {
        for n in nodes {
            self.known[n.index()] = true;
        }
    }

    /// The segment computing `roots`; with `only`, only the nodes it accepts (the others are
    /// left for a later segment).
    pub(crate) fn segment(
        &mut self,
        roots: &[NodeId],
        only: Option<&dyn Fn(NodeId) -> bool>,
    ) -> Result<Segment, Unavailable> {
        Ok(Segment::new(self.instructions(roots, only)?))
    }

    /// The segment computing `roots` as a Newton block's evaluation: each sine and cosine of one
    /// argument by a rotation slot of its own ([`Ins::NearSinCos`], see `crate::near`), the
    /// slots in fresh registers of `extra`. A lone sine or cosine stays libm's (the emitted
    /// evaluation pairs the same ones).
    pub(crate) fn near_segment(
        &mut self,
        roots: &[NodeId],
        extra: &mut Extra,
    ) -> Result<(Segment, NearSlots), Unavailable> {
        let ins = sin_cos(self.instructions(roots, None)?);
        let slots = NearSlots::new(extra, ins.iter().filter(|i| matches!(i, Ins::SinCos(..))).count());
        let mut k = 0;
        let ins = ins
            .into_iter()
            .map(|i| match i {
                Ins::SinCos(s, c, a) => {
                    k += 1;
                    Ins::NearSinCos(s, c, a, slots.slot(k - 1))
                }
                i => i,
            })
            .collect();
        Ok((Segment::of(ins), slots))
    }

    /// The instructions computing `roots` (see [`Builder::segment`]), one per graph operation.
    fn instructions(
        &mut self,
        roots: &[NodeId],
        only: Option<&dyn Fn(NodeId) -> bool>,
    ) -> Result<Vec<Ins>, Unavailable> {
        let mut out = Vec::new();
        let mut seen = vec![false; self.g.len()];
        let mut stack: Vec<NodeId> = roots.to_vec();
        let mut order = Vec::new();
        while let Some(n) = stack.pop() {
            if self.known[n.index()] || std::mem::replace(&mut seen[n.index()], true) {
                continue;
            }
            // A node left for a later segment is not computed here, but its operands may be.
            if only.is_none_or(|f| f(n)) {
                order.push(n);
            }
            // An angle sum's sine or cosine reads `sin a`, `cos a` and `b`, not the sum.
            stack.extend(sources(self.g, n));
        }
        // A sine or cosine brings its partner of the same argument, when the graph has one that
        // no segment computed yet: the two are then one instruction (one libm call for both)
        // instead of one here and one in a later segment. The partner's value is the same
        // wherever it is computed.
        for k in 0..order.len() {
            let partner = match self.g.op(order[k]) {
                Op::Func(Func::Sin, a) => self.g.find(Op::Func(Func::Cos, a)),
                Op::Func(Func::Cos, a) => self.g.find(Op::Func(Func::Sin, a)),
                _ => None,
            };
            if let Some(p) = partner
                && !self.known[p.index()]
                && !std::mem::replace(&mut seen[p.index()], true)
                && only.is_none_or(|f| f(p))
            {
                order.push(p);
            }
        }
        order.sort_unstable();
        let order = sums_after_their_parts(self.g, order);
        for n in order {
            let d = n.0;
            let o = |x: NodeId| x.0;
            if let Some(AngleSum { sin_a, cos_a, sin_b, cos_b, sine, .. }) = angle_sum(self.g, n) {
                let parts = [o(sin_a), o(cos_a), o(sin_b), o(cos_b)];
                out.push(if sine { Ins::SinSum(d, parts) } else { Ins::CosSum(d, parts) });
                continue;
            }
            out.push(match self.g.op(n) {
                Op::Const(_) => continue,
                Op::Leaf(l) => return Err(Unavailable(l)),
                Op::Add(a, b) => Ins::Add(d, o(a), o(b)),
                Op::Sub(a, b) => Ins::Sub(d, o(a), o(b)),
                Op::Mul(a, b) => Ins::Mul(d, o(a), o(b)),
                Op::Div(a, b) => Ins::Div(d, o(a), o(b)),
                Op::Neg(a) => Ins::Neg(d, o(a)),
                Op::Powi(a, 2) => Ins::Square(d, o(a)),
                Op::Powi(a, -1) => Ins::Recip(d, o(a)),
                Op::Powi(a, k) => Ins::Powi(d, o(a), k),
                Op::Powf(a, b) => Ins::Powf(d, o(a), o(b)),
                Op::Func(f, a) => {
                    let a = o(a);
                    match f {
                        Func::Sin => Ins::Sin(d, a),
                        Func::Cos => Ins::Cos(d, a),
                        Func::Tan => Ins::Tan(d, a),
                        Func::Asin => Ins::Asin(d, a),
                        Func::Acos => Ins::Acos(d, a),
                        Func::Atan => Ins::Atan(d, a),
                        Func::Sqrt => Ins::Sqrt(d, a),
                        Func::Exp => Ins::Exp(d, a),
                        Func::Ln => Ins::Ln(d, a),
                        Func::Abs => Ins::Abs(d, a),
                        Func::Signum => Ins::Signum(d, a),
                        Func::Floor => Ins::Floor(d, a),
                    }
                }
                Op::Atan2(y, x) => Ins::Atan2(d, o(y), o(x)),
                Op::Select(a, b, x, y) => Ins::Select(d, o(a), o(b), o(x), o(y)),
            });
        }
        for ins in &out {
            // The first register an unmerged instruction names is the one it writes.
            if let Some(d) = ins.registers().next() {
                self.known[d as usize] = true;
            }
        }
        Ok(out)
    }
}

/// `order` (nodes in increasing order) with each angle sum's `sin a`, `cos a`, `sin b` and
/// `cos b` moved before the sum's sine or cosine where they came after it (as the emitter emits
/// them), each by its own parts first where `a` is a sum itself: they read `a` and `b` alone,
/// which come before the sum `a + b`.
fn sums_after_their_parts(g: &Graph, order: Vec<NodeId>) -> Vec<NodeId> {
    fn place(g: &Graph, m: NodeId, pending: &HashSet<NodeId>, placed: &mut HashSet<NodeId>, out: &mut Vec<NodeId>) {
        if !pending.contains(&m) || placed.contains(&m) {
            return;
        }
        if let Some(sum) = angle_sum(g, m) {
            for part in [sum.sin_a, sum.cos_a, sum.sin_b, sum.cos_b] {
                place(g, part, pending, placed, out);
            }
        }
        placed.insert(m);
        out.push(m);
    }
    let pending: HashSet<NodeId> = order.iter().copied().collect();
    let mut placed: HashSet<NodeId> = HashSet::new();
    let mut out = Vec::with_capacity(order.len());
    for n in order {
        place(g, n, &pending, &mut placed, &mut out);
    }
    out
}

/// The registers of a graph with its constants written.
pub(crate) fn registers(g: &Graph) -> Vec<f64> {
    (0..g.len()).map(|k| g.as_const(NodeId(k as u32)).unwrap_or(0.0)).collect()
}

/// Per node: whether its value depends on the parameters and constants alone (the graph's
/// order is topological: operands come before their users).
fn fixed(g: &Graph) -> Vec<bool> {
    let mut fixed = vec![false; g.len()];
    for k in 0..g.len() {
        let op = g.op(NodeId(k as u32));
        fixed[k] = match op {
            Op::Const(_) | Op::Leaf(Leaf::Param(_)) => true,
            Op::Leaf(_) => false,
            _ => op.operands().all(|o| fixed[o.index()]),
        };
    }
    fixed
}

/// The segment computing every node of the parameters alone, run when the parameters are set:
/// the compiled step computes these nodes on every call, with the same operations, so hoisting
/// them out of the step changes no value.
pub(crate) fn statics(g: &Graph) -> Segment {
    let fixed = fixed(g);
    let roots: Vec<NodeId> = (0..g.len()).filter(|&k| fixed[k]).map(|k| NodeId(k as u32)).collect();
    let mut b = Builder {
        g,
        known: (0..g.len())
            .map(|k| matches!(g.op(NodeId(k as u32)), Op::Const(_) | Op::Leaf(Leaf::Param(_))))
            .collect(),
    };
    // Every operand of a fixed node is fixed: no leaf but a parameter is reached.
    b.segment(&roots, None).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use kinloop_codegen::graph::dag::Func;

    /// The merged and grouped instructions compute what the separate operations compute, bit for
    /// bit: the reference is the same expression written out in Rust, as the emitted code
    /// writes it.
    #[test]
    fn merged_and_grouped_instructions_give_the_separate_operations_values() {
        let mut g = Graph::new();
        let x = g.leaf(Leaf::Input(0));
        let y = g.leaf(Leaf::Input(1));
        let p = g.leaf(Leaf::Param(0));
        let sx = g.func(Func::Sin, x);
        let cx = g.func(Func::Cos, x);
        let a = g.mul(p, sx);
        let b = g.mul(y, cx);
        let s = g.add(a, b);
        let d = g.sub(x, y);
        let e = g.add(x, y);
        let q = g.div(d, e);
        let pp = g.mul(p, p);
        let pp = g.func(Func::Sqrt, pp);
        let t = g.mul(q, pp);
        let roots = [s, t];

        let statics = statics(&g);
        let seg = Builder::new(&g).segment(&roots, None).expect("every leaf is known");
        // The sine and cosine are one step, the seven arithmetic operations two (4 + 3), the
        // parameters' nodes hoisted: three steps for nine operations.
        assert_eq!(seg.len(), 9, "{seg:?}");
        assert_eq!(dispatches(&seg), 3, "{seg:?}");
        assert!(seg.steps.iter().any(|s| std::ptr::fn_addr_eq(s.exec, sin_cos_step as Exec)), "{seg:?}");

        for (xv, yv, pv) in [(0.3, -1.7, 2.5), (1e-3, 4.0, -0.7), (-2.9, 1e5, 1e-9)] {
            let mut r = registers(&g);
            r[x.index()] = xv;
            r[y.index()] = yv;
            r[p.index()] = pv;
            statics.run(&mut r);
            seg.run(&mut r);
            let (sin, cos) = xv.sin_cos();
            let want_s = pv * sin + yv * cos;
            let want_t = ((xv - yv) / (xv + yv)) * (pv * pv).sqrt();
            assert_eq!(r[s.index()].to_bits(), want_s.to_bits());
            assert_eq!(r[t.index()].to_bits(), want_t.to_bits());
        }
    }

    /// The steps of a segment that perform instructions (not the chains' ends).
    fn dispatches(seg: &Segment) -> usize {
        seg.steps.iter().filter(|s| s.r != END).count()
    }

    /// A segment of many steps (several chains) performs every instruction once, in order, and
    /// its steps are chained as [`CHAIN`] says.
    #[test]
    fn a_long_segment_runs_every_chain_in_order() {
        // Register k + 1 from register k: three subtractions of register 0, then an absolute
        // value (a step of its own), 200 instructions, 100 steps.
        let n = 200;
        let ins: Vec<Ins> =
            (0..n as u32).map(|k| if k % 4 == 3 { Ins::Abs(k + 1, k) } else { Ins::Sub(k + 1, k, 0) }).collect();
        let seg = Segment::of(ins);
        assert_eq!(dispatches(&seg), 100);
        assert_eq!(seg.steps.len(), 100 + 100usize.div_ceil(CHAIN));
        for x in [0.3, -2.0, 1e-3] {
            let mut r = vec![0.0; n + 1];
            r[0] = x;
            seg.run(&mut r);
            let mut want = x;
            for k in 0..n {
                want = if k % 4 == 3 { want.abs() } else { want - x };
                assert_eq!(r[k + 1].to_bits(), want.to_bits(), "register {}", k + 1);
            }
        }
    }

    /// The operation of code `k` as the emitted code writes it (the reference for the grouped
    /// steps: separate Rust operations, each rounded on its own).
    fn reference(k: u8, a: f64, b: f64) -> f64 {
        match k {
            0 => a + b,
            1 => a - b,
            2 => a * b,
            3 => a / b,
            _ => -a,
        }
    }

    /// Every grouped step (one to four arithmetic operations of every kind) computes the
    /// separate operations' values bit for bit, in their order: each operation reads what the
    /// one before it wrote, and the inputs are such that reassociating (`(a + b) - c` against
    /// `a + (b - c)` at `a = 1, b = c = 1e16`), contracting a product and a sum into one
    /// rounding or reading a register before it is written would change the result.
    /// A group whose operations write registers in place and overwrite what an earlier one
    /// read performs them one after the other, as separate statements do: the sequential
    /// contract a closed form's program relies on once its registers are reused.
    #[test]
    fn a_group_writing_registers_in_place_runs_its_operations_in_order() {
        // r0 = r0 + r1; r1 = r0 * r1; r0 = r1 - r0; r2 = r0 / r1.
        let ins = vec![Ins::Add(0, 0, 1), Ins::Mul(1, 0, 1), Ins::Sub(0, 1, 0), Ins::Div(2, 0, 1)];
        let seg = Segment::of(ins);
        assert_eq!(dispatches(&seg), 1);
        for [a, b] in [[0.1, 0.2], [1e16, 1.0], [-3.0, 7.5e-8]] {
            let mut r = [a, b, 0.0];
            seg.run(&mut r);
            let (mut x, mut y) = (a, b);
            x += y;
            y *= x;
            x = y - x;
            let z = x / y;
            assert_eq!(r.map(f64::to_bits), [x, y, z].map(f64::to_bits), "at {a}, {b}");
        }
    }

    #[test]
    fn grouped_arithmetic_steps_give_the_separate_operations_values() {
        let inputs: [[f64; 5]; 4] = [
            [1.0, 1e16, 1e16, 0.1, -3.0],
            // (1 + 2^-30)^2 - (1 + 2^-29) is 2^-60 exactly, rounded to 0 when the product is
            // rounded first.
            [1.0 + 2f64.powi(-30), 1.0 + 2f64.powi(-30), 1.0 + 2f64.powi(-29), 3.0, 1e-5],
            [0.1, 0.2, 0.3, -7.0, 0.7],
            [-2.5e-300, 1e300, 1e-10, 1e10, 1e300],
        ];
        let codes = [ADD, SUB, MUL, DIV, NEG];
        let mut groups: Vec<Vec<u8>> = vec![vec![]];
        for len in 1..=4 {
            let longer: Vec<Vec<u8>> = groups
                .iter()
                .filter(|g| g.len() == len - 1)
                .flat_map(|g| codes.map(|k| [g.clone(), vec![k]].concat()))
                .collect();
            groups.extend(longer);
        }
        groups.remove(0);
        assert_eq!(groups.len(), 5 + 25 + 125 + 625);
        for group in &groups {
            // Registers 0..5 the inputs, 5.. the results: operation `j` reads the previous
            // result (or input 0) and input `j + 1`, and writes register `5 + j`.
            let ins: Vec<Ins> = group
                .iter()
                .enumerate()
                .map(|(j, &k)| {
                    let (d, a, b) = (5 + j as u32, if j == 0 { 0 } else { 4 + j as u32 }, 1 + j as u32);
                    match k {
                        ADD => Ins::Add(d, a, b),
                        SUB => Ins::Sub(d, a, b),
                        MUL => Ins::Mul(d, a, b),
                        DIV => Ins::Div(d, a, b),
                        _ => Ins::Neg(d, a),
                    }
                })
                .collect();
            let seg = Segment::of(ins);
            assert_eq!(dispatches(&seg), 1, "one step for {group:?}");
            for x in inputs {
                let mut r = [x[0], x[1], x[2], x[3], x[4], 0.0, 0.0, 0.0, 0.0];
                seg.run(&mut r);
                let mut prev = x[0];
                for (j, &k) in group.iter().enumerate() {
                    prev = reference(k, prev, x[j + 1]);
                    assert_eq!(r[5 + j].to_bits(), prev.to_bits(), "{group:?} at {x:?}, operation {j}");
                }
            }
        }
        // The inputs tell the orders apart.
        let [a, b, c, ..] = inputs[0];
        assert_ne!((a + b) - c, a + (b - c));
        let [a, b, c, ..] = inputs[1];
        assert_ne!((a * b) - c, a.mul_add(b, -c));
    }

    /// A long run of arithmetic operations is cut into steps of four, in order, and the
    /// instructions around it stay steps of their own.
    #[test]
    fn a_run_is_grouped_by_four_between_other_instructions() {
        let ins = vec![
            Ins::Sin(1, 0),
            Ins::Add(2, 0, 1),
            Ins::Mul(3, 2, 2),
            Ins::Neg(4, 3),
            Ins::Sub(5, 0, 4),
            Ins::Add(6, 5, 0),
            Ins::Mul(7, 6, 1),
            Ins::Sqrt(8, 5),
            Ins::Div(9, 8, 1),
        ];
        let seg = Segment::of(ins);
        // The sine, four and two arithmetic operations, the square root, the division.
        assert_eq!(dispatches(&seg), 5);
        assert_eq!((seg.len(), seg.needs), (9, 10));
        for x in [0.7, -1.3, 1e-8] {
            let mut r = [x, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
            seg.run(&mut r);
            let s = x.sin();
            let t = x + s;
            let u = -(t * t);
            let v = x - u;
            let w = v.sqrt();
            let want = [x, s, t, t * t, u, v, v + x, (v + x) * s, w, w / s];
            assert_eq!(r.map(f64::to_bits), want.map(f64::to_bits));
        }
    }

    /// Chains entered by their starts execute their instructions as a segment does: a run too
    /// long for one chain is several, executed in order, and a second run's chain is entered
    /// without running the first's.
    #[test]
    fn chains_run_from_their_starts() {
        let n = 4 * CHAIN + 5;
        let long: Vec<Ins> = (0..n as u32).map(|k| Ins::Mul(k + 1, k, 0)).collect();
        let mut chains = Chains::default();
        let starts = chains.push(&long);
        assert_eq!(starts.len(), 2);
        let other = chains.push(&[Ins::Add(n as u32 + 1, 0, 1), Ins::Neg(n as u32 + 2, n as u32 + 1)]);
        assert_eq!(other.len(), 1);
        assert_eq!(chains.needs(), n + 3);
        let x = 1.0 + 1e-3;
        let mut r = vec![0.0; n + 3];
        r[0] = x;
        for &s in &starts {
            // SAFETY: `s` from `push`, `r` holds `needs` registers.
            unsafe { chains.run(r.as_mut_ptr(), s) };
        }
        let mut want = x;
        for (k, got) in r.iter().enumerate().take(n + 1).skip(1) {
            want *= x;
            assert_eq!(got.to_bits(), want.to_bits(), "register {k}");
        }
        // The second run reads register 1, written by the first: entered alone after it.
        let before = r[1];
        // SAFETY: as above.
        unsafe { chains.run(r.as_mut_ptr(), other[0]) };
        let sum = x + before;
        assert_eq!([r[n + 1], r[n + 2]].map(f64::to_bits), [sum, -sum].map(f64::to_bits));
    }
}
