//! A block's factorisation at run time: the runtime's own types (`Fixed`, `Lu<N>`, `Inverse2`),
//! chosen by the emitter's rules, with the block size known only when the model is built.
//!
//! The runtime's factorisations are generic over the block size `N` (a constant of the compiled
//! code). At run time the size is dispatched once per call over `1..=MAX_DENSE`, so a block is
//! factorised and solved by the very code a compiled mechanism runs. A block solved by sparse
//! Newton holds its own solver and factorisation (`sparse`), of any size up to `MAX_SPARSE`.

use crate::sparse::SparseBlock;
use kinloop_runtime::generated::{Factor, Fixed, Health, Inverse2, Lu};

/// The largest dense block evaluated at run time (the runtime's types are instantiated for
/// every size up to it).
pub const MAX_DENSE: usize = 16;

/// One block's factorisation, of the type the emitted code would use. Factorisations of three
/// unknowns and more are boxed, allocated once for the block ([`Fac::for_size`]) and written in
/// place by every step: the enum stays small, so moving it costs no large copy.
#[derive(Clone, Debug)]
pub(crate) enum Fac {
    /// Not factorised yet.
    None,
    Fixed(Fixed),
    Inverse2(Inverse2),
    L1(Lu<1>),
    L2(Lu<2>),
    L3(Box<Lu<3>>),
    L4(Box<Lu<4>>),
    L5(Box<Lu<5>>),
    L6(Box<Lu<6>>),
    L7(Box<Lu<7>>),
    L8(Box<Lu<8>>),
    L9(Box<Lu<9>>),
    L10(Box<Lu<10>>),
    L11(Box<Lu<11>>),
    L12(Box<Lu<12>>),
    L13(Box<Lu<13>>),
    L14(Box<Lu<14>>),
    L15(Box<Lu<15>>),
    L16(Box<Lu<16>>),
    /// A block solved by sparse Newton: its solver and the analogs' factorisation.
    Sparse(Box<dyn SparseBlock>),
}

/// Calls `$f!(lu)` with the factorisation `lu` of whatever size `$fac` holds.
macro_rules! each_lu {
    ($fac:expr, $lu:ident => $body:expr, $other:pat => $alt:expr) => {
        match $fac {
            Fac::L1($lu) => $body,
            Fac::L2($lu) => $body,
            Fac::L3($lu) => $body,
            Fac::L4($lu) => $body,
            Fac::L5($lu) => $body,
            Fac::L6($lu) => $body,
            Fac::L7($lu) => $body,
            Fac::L8($lu) => $body,
            Fac::L9($lu) => $body,
            Fac::L10($lu) => $body,
            Fac::L11($lu) => $body,
            Fac::L12($lu) => $body,
            Fac::L13($lu) => $body,
            Fac::L14($lu) => $body,
            Fac::L15($lu) => $body,
            Fac::L16($lu) => $body,
            $other => $alt,
        }
    };
}

/// Copies a slice into an array of `N` (the caller's slices have the block's size).
fn array<const N: usize>(v: &[f64]) -> [f64; N] {
    let mut a = [0.0; N];
    a.copy_from_slice(&v[..N]);
    a
}

/// The place of a block's `Lu<N>` in its [`Fac`], made the first time (for the sizes that are
/// boxed: when the block's slot is made, [`Fac::for_size`]).
pub(crate) trait LuSlot<const N: usize> {
    /// The `Lu<N>` of `fac`, made unfactored if `fac` holds another kind.
    fn slot(fac: &mut Fac) -> &mut Lu<N>;
}

macro_rules! slots {
    ($($n:literal => $v:ident $(boxed $b:tt)?),*) => {$(
        impl LuSlot<$n> for Lu<$n> {
            fn slot(fac: &mut Fac) -> &mut Lu<$n> {
                if !matches!(fac, Fac::$v(_)) {
                    *fac = Fac::$v(slots!(@make $($b)?));
                }
                match fac {
                    Fac::$v(lu) => lu,
                    // Made just above.
                    _ => unreachable!(),
                }
            }
        }
    )*};
    (@make) => { Lu::unfactored() };
    (@make $b:tt) => { Box::new(Lu::unfactored()) };
}
slots!(1 => L1, 2 => L2, 3 => L3 boxed x, 4 => L4 boxed x, 5 => L5 boxed x, 6 => L6 boxed x, 7 => L7 boxed x, 8 => L8 boxed x,
    9 => L9 boxed x, 10 => L10 boxed x, 11 => L11 boxed x, 12 => L12 boxed x, 13 => L13 boxed x, 14 => L14 boxed x, 15 => L15 boxed x, 16 => L16 boxed x
);

impl Fac {
    /// The slot of a block of `n` unknowns: its boxed `Lu` made once, where it has one.
    pub(crate) fn for_size(n: usize) -> Fac {
        match n {
            3 => Fac::L3(Box::new(Lu::unfactored())),
            4 => Fac::L4(Box::new(Lu::unfactored())),
            5 => Fac::L5(Box::new(Lu::unfactored())),
            6 => Fac::L6(Box::new(Lu::unfactored())),
            7 => Fac::L7(Box::new(Lu::unfactored())),
            8 => Fac::L8(Box::new(Lu::unfactored())),
            9 => Fac::L9(Box::new(Lu::unfactored())),
            10 => Fac::L10(Box::new(Lu::unfactored())),
            11 => Fac::L11(Box::new(Lu::unfactored())),
            12 => Fac::L12(Box::new(Lu::unfactored())),
            13 => Fac::L13(Box::new(Lu::unfactored())),
            14 => Fac::L14(Box::new(Lu::unfactored())),
            15 => Fac::L15(Box::new(Lu::unfactored())),
            16 => Fac::L16(Box::new(Lu::unfactored())),
            _ => Fac::None,
        }
    }

    /// `Lu::factor_cols` of the `n x n` matrix whose entry `k` in row-major order is `entry(k)`,
    /// with column scales `scale`, written into this slot; `Lu::factor_scaled` with row scales
    /// `rows` where there are any (a block whose rows have more than one unit).
    pub(crate) fn factor_cols(&mut self, n: usize, entry: impl Fn(usize) -> f64, rows: &[f64], scale: &[f64]) {
        macro_rules! f {
            ($n:literal) => {{
                let m: [[f64; $n]; $n] = std::array::from_fn(|i| std::array::from_fn(|j| entry(i * $n + j)));
                *<Lu<$n> as LuSlot<$n>>::slot(self) = if rows.is_empty() {
                    Lu::<$n>::factor_cols(&m, array::<$n>(scale))
                } else {
                    Lu::<$n>::factor_scaled(&m, array::<$n>(rows), array::<$n>(scale))
                }
            }};
        }
        match n {
            1 => f!(1),
            2 => f!(2),
            3 => f!(3),
            4 => f!(4),
            5 => f!(5),
            6 => f!(6),
            7 => f!(7),
            8 => f!(8),
            9 => f!(9),
            10 => f!(10),
            11 => f!(11),
            12 => f!(12),
            13 => f!(13),
            14 => f!(14),
            15 => f!(15),
            16 => f!(16),
            _ => *self = Fac::None,
        }
    }

    /// `Lu::<1>::factor_in_col` of the scalar `entry`, its column's largest magnitude `col_max`
    /// (the emitted code passes the whole column, whose `max_abs` it is), written into this
    /// slot in place: the slot keeps its kind from step to step, so the old value is neither
    /// dropped nor the whole enum moved.
    #[inline]
    pub(crate) fn set_in_col(&mut self, entry: f64, col_max: f64) -> Lu<1> {
        let lu = Lu::<1>::factor_in_col([entry, col_max], 0);
        self.put_l1(lu);
        lu
    }

    /// Writes the 1x1 factorisation `lu` into this slot, in place as by [`Fac::set_in_col`].
    #[inline(always)]
    pub(crate) fn put_l1(&mut self, lu: Lu<1>) {
        match self {
            Fac::L1(slot) => *slot = lu,
            other => *other = Fac::L1(lu),
        }
    }

    /// `Inverse2::in_cols_floored` of `j` with each column's largest magnitude beyond the block
    /// (`None`: the columns have no entries beyond it) and its floor. The emitted code passes
    /// the entries themselves; their largest magnitude gives the same maximum, and the same
    /// verdict on a non-finite entry, except where finite entries beyond the block sum to an
    /// infinity (magnitudes near `f64::MAX`), which the compiled test would call singular.
    #[inline(always)]
    pub(crate) fn inverse2(j: &[[f64; 2]; 2], beyond: Option<[f64; 2]>, floor: [Option<f64>; 2]) -> Inverse2 {
        match beyond {
            None => Inverse2::in_cols_floored::<0>(j, [[]; 2], floor),
            Some([b0, b1]) => Inverse2::in_cols_floored::<1>(j, [[b0], [b1]], floor),
        }
    }

    /// Writes the 2x2 inverse `inv` into this slot, in place as by [`Fac::set_in_col`].
    #[inline(always)]
    pub(crate) fn put_inverse2(&mut self, inv: Inverse2) {
        match self {
            Fac::Inverse2(slot) => *slot = inv,
            other => *other = Fac::Inverse2(inv),
        }
    }

    /// The smallest pivot of the equilibrated matrix (0 when singular or not factorised).
    pub(crate) fn pivot_ratio(&self) -> f64 {
        each_lu!(self, lu => lu.pivot_ratio(), other => match other {
            Fac::Fixed(f) => f.pivot_ratio(),
            Fac::Inverse2(f) => f.pivot_ratio(),
            Fac::Sparse(s) => s.pivot_ratio(),
            _ => 0.0,
        })
    }

    /// The pivot ratio and determinant sign, read with one match on the kind (`None` for a
    /// sparse block, which notes its own, and for no factorisation). Inlined in the block's
    /// step: a call per block cost more than the match.
    #[inline(always)]
    pub(crate) fn conditioning(&self) -> Option<Conditioning> {
        let c = |pivot_ratio: f64, negative_det: bool| Some(Conditioning { pivot_ratio, negative_det });
        each_lu!(self, lu => c(lu.pivot_ratio(), lu.negative_det()), other => match other {
            Fac::Fixed(f) => c(f.pivot_ratio(), f.negative_det()),
            Fac::Inverse2(f) => c(Factor::pivot_ratio(f), f.negative_det()),
            _ => None,
        })
    }

    /// Records the factorisation's conditioning for block `b`.
    pub(crate) fn note(&self, health: &mut Health, b: usize) {
        match self {
            Fac::Fixed(f) => health.note(b, f),
            Fac::Inverse2(f) => health.note(b, f),
            Fac::L1(lu) => health.note(b, lu),
            Fac::L2(lu) => health.note(b, lu),
            Fac::L3(lu) => health.note(b, &**lu),
            Fac::L4(lu) => health.note(b, &**lu),
            Fac::L5(lu) => health.note(b, &**lu),
            Fac::L6(lu) => health.note(b, &**lu),
            Fac::L7(lu) => health.note(b, &**lu),
            Fac::L8(lu) => health.note(b, &**lu),
            Fac::L9(lu) => health.note(b, &**lu),
            Fac::L10(lu) => health.note(b, &**lu),
            Fac::L11(lu) => health.note(b, &**lu),
            Fac::L12(lu) => health.note(b, &**lu),
            Fac::L13(lu) => health.note(b, &**lu),
            Fac::L14(lu) => health.note(b, &**lu),
            Fac::L15(lu) => health.note(b, &**lu),
            Fac::L16(lu) => health.note(b, &**lu),
            Fac::Sparse(s) => s.note(health, b),
            Fac::None => {}
        }
    }

    /// Solves the 1x1 `J z = rhs` (a block of one unknown: `Fixed`, `Lu<1>`).
    #[inline]
    pub(crate) fn solve1(&self, rhs: f64) -> f64 {
        match self {
            Fac::Fixed(f) => f.solve([rhs])[0],
            Fac::L1(lu) => lu.solve([rhs])[0],
            other => {
                let mut z = [rhs];
                other.solve(&mut z);
                z[0]
            }
        }
    }

    /// Solves the 2x2 `J z = rhs` (a block of two unknowns: `Inverse2`, `Lu<2>`), with no copy
    /// through a slice.
    #[inline]
    pub(crate) fn solve2(&self, rhs: [f64; 2]) -> [f64; 2] {
        match self {
            Fac::Inverse2(f) => f.solve(rhs),
            Fac::L2(lu) => lu.solve(rhs),
            other => {
                let mut z = rhs;
                other.solve(&mut z);
                z
            }
        }
    }

    /// Solves `J z = rhs` in place (`rhs.len()` is the block's size).
    pub(crate) fn solve(&self, rhs: &mut [f64]) {
        macro_rules! s {
            ($lu:expr, $n:literal) => {{
                let z = $lu.solve(array::<$n>(rhs));
                rhs.copy_from_slice(&z);
            }};
        }
        match self {
            Fac::Fixed(f) => rhs[0] = f.solve([rhs[0]])[0],
            Fac::Inverse2(f) => s!(f, 2),
            Fac::L1(lu) => s!(lu, 1),
            Fac::L2(lu) => s!(lu, 2),
            Fac::L3(lu) => s!(lu, 3),
            Fac::L4(lu) => s!(lu, 4),
            Fac::L5(lu) => s!(lu, 5),
            Fac::L6(lu) => s!(lu, 6),
            Fac::L7(lu) => s!(lu, 7),
            Fac::L8(lu) => s!(lu, 8),
            Fac::L9(lu) => s!(lu, 9),
            Fac::L10(lu) => s!(lu, 10),
            Fac::L11(lu) => s!(lu, 11),
            Fac::L12(lu) => s!(lu, 12),
            Fac::L13(lu) => s!(lu, 13),
            Fac::L14(lu) => s!(lu, 14),
            Fac::L15(lu) => s!(lu, 15),
            Fac::L16(lu) => s!(lu, 16),
            Fac::Sparse(s) => s.solve(rhs),
            Fac::None => rhs.fill(f64::NAN),
        }
    }
}

/// What `Health::note` reads of a factorisation, read once ([`Fac::conditioning`]): the same
/// values its own `Factor` methods give.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Conditioning {
    pub(crate) pivot_ratio: f64,
    negative_det: bool,
}

impl Factor for Conditioning {
    #[inline]
    fn pivot_ratio(&self) -> f64 {
        self.pivot_ratio
    }
    #[inline]
    fn negative_det(&self) -> bool {
        self.negative_det
    }
}

/// The largest magnitude among `v`, or NaN when one is NaN: the runtime's `max_abs` over a
/// slice (a select per value, which skips a NaN, and a sum, which does not).
pub(crate) fn max_abs(v: impl IntoIterator<Item = f64>) -> f64 {
    let (mut m, mut sum) = (0.0f64, -0.0f64);
    for x in v {
        let x = x.abs();
        m = if x > m { x } else { m };
        sum += x;
    }
    if sum.is_nan() { f64::NAN } else { m }
}
