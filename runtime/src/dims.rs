//! How a mechanism's sizes are known: when it is compiled ([`Fixed`], arrays of today's sizes,
//! zero-sized) or when it is read at run time ([`Sizes`], boxed slices allocated once per sweep).
//!
//! The runtime's sweep, its event location and its table are written once, over a
//! [`Kernel`](crate::Kernel) whose storage types come from its [`Dims`]: a compiled mechanism's
//! sweep holds the very arrays it held before (its loops have constant trip counts and unroll),
//! and a run-time model's the same algorithm over slices whose lengths it learns when read.

use crate::kin::{Health, Jac, Kin};
use crate::solvers::lu::Lu;
use crate::solvers::newton::SolveReport;
use std::fmt;
use std::ops::{Index, IndexMut};

/// A vector of one of a mechanism's sizes: `[f64; N]` when compiled, [`Heap`] at run time.
pub trait Store:
    Clone + fmt::Debug + Index<usize, Output = f64> + IndexMut<usize> + AsRef<[f64]> + AsMut<[f64]>
{
}

impl<const K: usize> Store for [f64; K] {}

/// A square matrix of the inputs' size, `m[i][j]`: `[[f64; NI]; NI]` when compiled, [`Heap2`]
/// at run time.
pub trait Square: Clone + fmt::Debug {
    /// Entry `(i, j)`.
    fn at(&self, i: usize, j: usize) -> f64;
    /// Sets entry `(i, j)`.
    fn set(&mut self, i: usize, j: usize, v: f64);
}

impl<const K: usize> Square for [[f64; K]; K] {
    #[inline(always)]
    fn at(&self, i: usize, j: usize) -> f64 {
        self[i][j]
    }
    #[inline(always)]
    fn set(&mut self, i: usize, j: usize, v: f64) {
        self[i][j] = v;
    }
}

/// A vector whose length is known at run time: a boxed slice, allocated once (a sweep's
/// workspace), never grown.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Heap(pub Box<[f64]>);

impl Heap {
    /// `len` zeros.
    pub fn zeros(len: usize) -> Self {
        Heap(vec![0.0; len].into_boxed_slice())
    }
}

impl Index<usize> for Heap {
    type Output = f64;
    #[inline]
    fn index(&self, i: usize) -> &f64 {
        &self.0[i]
    }
}

impl IndexMut<usize> for Heap {
    #[inline]
    fn index_mut(&mut self, i: usize) -> &mut f64 {
        &mut self.0[i]
    }
}

impl AsRef<[f64]> for Heap {
    #[inline]
    fn as_ref(&self) -> &[f64] {
        &self.0
    }
}

impl AsMut<[f64]> for Heap {
    #[inline]
    fn as_mut(&mut self) -> &mut [f64] {
        &mut self.0
    }
}

impl Store for Heap {}

/// A square matrix whose size is known at run time, by rows.
#[derive(Clone, Debug, PartialEq)]
pub struct Heap2 {
    values: Box<[f64]>,
    size: usize,
}

impl Heap2 {
    /// A `size` by `size` matrix of zeros.
    pub fn zeros(size: usize) -> Self {
        Heap2 { values: vec![0.0; size * size].into_boxed_slice(), size }
    }
}

impl Square for Heap2 {
    #[inline]
    fn at(&self, i: usize, j: usize) -> f64 {
        self.values[i * self.size + j]
    }
    #[inline]
    fn set(&mut self, i: usize, j: usize, v: f64) {
        self.values[i * self.size + j] = v;
    }
}

/// A kinematic state as the generic algorithms read it: [`Kin`] when compiled, [`KinBuf`] at
/// run time.
pub trait KinState: Clone + fmt::Debug {
    /// The inputs.
    fn x(&self) -> &[f64];
    /// The positions of the unknowns.
    fn q(&self) -> &[f64];
    /// The velocity analogs of unknown `u`, one per input.
    fn dq(&self, u: usize) -> &[f64];
    /// The acceleration analog `d2 q_u / d x_i d x_j`.
    fn d2q(&self, u: usize, i: usize, j: usize) -> f64;
    /// The output columns.
    fn out(&self) -> &[f64];
    /// The velocity analogs of output column `o`, one per input.
    fn dout(&self, o: usize) -> &[f64];
    /// The acceleration analog `d2 out_o / d x_i d x_j`.
    fn d2out(&self, o: usize, i: usize, j: usize) -> f64;
    /// The conditioning of the blocks.
    fn health(&self) -> &Health;
    /// The position solve's report.
    fn report(&self) -> &SolveReport;
    /// The state as one table row, in the order of the table's columns (see
    /// [`Table::kin_row`](crate::Table::kin_row)).
    fn table_row(&self) -> Vec<f64>;
    /// The bytes the state holds beyond its own `size_of` (on the heap): with it, what keeping
    /// the state costs (a sweep's `run` budgets its states by it). None for [`Kin`], whose arrays
    /// are inline.
    fn heap_bytes(&self) -> usize {
        0
    }
}

impl<const N: usize, const NI: usize, const NO: usize> KinState for Kin<N, NI, NO> {
    #[inline(always)]
    fn x(&self) -> &[f64] {
        &self.x
    }
    #[inline(always)]
    fn q(&self) -> &[f64] {
        &self.q
    }
    #[inline(always)]
    fn dq(&self, u: usize) -> &[f64] {
        &self.dq[u]
    }
    #[inline(always)]
    fn d2q(&self, u: usize, i: usize, j: usize) -> f64 {
        self.d2q[u][i][j]
    }
    #[inline(always)]
    fn out(&self) -> &[f64] {
        &self.out
    }
    #[inline(always)]
    fn dout(&self, o: usize) -> &[f64] {
        &self.dout[o]
    }
    #[inline(always)]
    fn d2out(&self, o: usize, i: usize, j: usize) -> f64 {
        self.d2out[o][i][j]
    }
    #[inline(always)]
    fn health(&self) -> &Health {
        &self.health
    }
    #[inline(always)]
    fn report(&self) -> &SolveReport {
        &self.report
    }
    fn table_row(&self) -> Vec<f64> {
        crate::Table::kin_row(self)
    }
}

/// A kinematic state whose sizes are known at run time: the fields of [`Kin`] flat, analogs by
/// rows (`dq[u * ni + i]`, `d2q[(u * ni + i) * ni + j]`, the same for the outputs).
#[derive(Clone, Debug, PartialEq)]
pub struct KinBuf {
    /// Inputs.
    pub x: Box<[f64]>,
    /// Positions of the unknowns.
    pub q: Box<[f64]>,
    /// `dq[u * ni + i] = d q_u / d x_i`.
    pub dq: Box<[f64]>,
    /// `d2q[(u * ni + i) * ni + j] = d2 q_u / d x_i d x_j`.
    pub d2q: Box<[f64]>,
    /// Output columns.
    pub out: Box<[f64]>,
    /// `dout[o * ni + i]`.
    pub dout: Box<[f64]>,
    /// `d2out[(o * ni + i) * ni + j]`.
    pub d2out: Box<[f64]>,
    /// The position solve's report.
    pub report: SolveReport,
    /// Conditioning of the blocks.
    pub health: Health,
}

impl KinBuf {
    /// A state of zeros of the sizes `d`.
    pub fn zeros(d: Sizes) -> Self {
        let z = |len: usize| vec![0.0; len].into_boxed_slice();
        KinBuf {
            x: z(d.ni),
            q: z(d.n),
            dq: z(d.n * d.ni),
            d2q: z(d.n * d.ni * d.ni),
            out: z(d.no),
            dout: z(d.no * d.ni),
            d2out: z(d.no * d.ni * d.ni),
            report: SolveReport::direct(),
            health: Health::default(),
        }
    }
}

impl KinState for KinBuf {
    #[inline]
    fn x(&self) -> &[f64] {
        &self.x
    }
    #[inline]
    fn q(&self) -> &[f64] {
        &self.q
    }
    #[inline]
    fn dq(&self, u: usize) -> &[f64] {
        let ni = self.x.len();
        &self.dq[u * ni..(u + 1) * ni]
    }
    #[inline]
    fn d2q(&self, u: usize, i: usize, j: usize) -> f64 {
        let ni = self.x.len();
        self.d2q[(u * ni + i) * ni + j]
    }
    #[inline]
    fn out(&self) -> &[f64] {
        &self.out
    }
    #[inline]
    fn dout(&self, o: usize) -> &[f64] {
        let ni = self.x.len();
        &self.dout[o * ni..(o + 1) * ni]
    }
    #[inline]
    fn d2out(&self, o: usize, i: usize, j: usize) -> f64 {
        let ni = self.x.len();
        self.d2out[(o * ni + i) * ni + j]
    }
    #[inline]
    fn health(&self) -> &Health {
        &self.health
    }
    #[inline]
    fn report(&self) -> &SolveReport {
        &self.report
    }
    fn table_row(&self) -> Vec<f64> {
        crate::Table::state_row(
            self.x.len(),
            &self.x,
            [(&self.q, &self.dq, &self.d2q), (&self.out, &self.dout, &self.d2out)],
        )
    }
    fn heap_bytes(&self) -> usize {
        let values = [&self.x, &self.q, &self.dq, &self.d2q, &self.out, &self.dout, &self.d2out].map(|v| v.len());
        values.iter().sum::<usize>() * size_of::<f64>()
    }
}

/// Residuals and first derivatives of all equations as the generic algorithms read them:
/// [`Jac`] when compiled, [`JacBuf`] at run time.
pub trait JacState: Clone + fmt::Debug {
    /// Residual `f_e`.
    fn f(&self, e: usize) -> f64;
    /// `df_e / dq_u`.
    fn j(&self, e: usize, u: usize) -> f64;
    /// `df_e / dx_i`.
    fn fx(&self, e: usize, i: usize) -> f64;
    /// The magnitude of equation `e`'s terms (see [`Jac::scale`]).
    fn scale(&self, e: usize) -> f64;
    /// The unit of unknown `u` (see [`Jac::unit`]).
    fn unit(&self, u: usize) -> f64;
    /// The unit of input `i` (see [`Jac::input_unit`]).
    fn input_unit(&self, i: usize) -> f64;
}

impl<const N: usize, const NI: usize> JacState for Jac<N, NI> {
    #[inline(always)]
    fn f(&self, e: usize) -> f64 {
        self.f[e]
    }
    #[inline(always)]
    fn j(&self, e: usize, u: usize) -> f64 {
        self.j[e][u]
    }
    #[inline(always)]
    fn fx(&self, e: usize, i: usize) -> f64 {
        self.fx[e][i]
    }
    #[inline(always)]
    fn scale(&self, e: usize) -> f64 {
        self.scale[e]
    }
    #[inline(always)]
    fn unit(&self, u: usize) -> f64 {
        self.unit[u]
    }
    #[inline(always)]
    fn input_unit(&self, i: usize) -> f64 {
        self.input_unit[i]
    }
}

/// [`Jac`] with its sizes known at run time: `j[e * n + u]`, `fx[e * ni + i]`.
#[derive(Clone, Debug, PartialEq)]
pub struct JacBuf {
    /// Residuals `f_e`.
    pub f: Box<[f64]>,
    /// `j[e * n + u] = df_e / dq_u`.
    pub j: Box<[f64]>,
    /// `fx[e * ni + i] = df_e / dx_i`.
    pub fx: Box<[f64]>,
    /// Magnitude of each equation's terms.
    pub scale: Box<[f64]>,
    /// The unit of each unknown.
    pub unit: Box<[f64]>,
    /// The unit of each input.
    pub input_unit: Box<[f64]>,
}

impl JacBuf {
    /// Zeros of the sizes `d`.
    pub fn zeros(d: Sizes) -> Self {
        let z = |len: usize| vec![0.0; len].into_boxed_slice();
        JacBuf { f: z(d.n), j: z(d.n * d.n), fx: z(d.n * d.ni), scale: z(d.n), unit: z(d.n), input_unit: z(d.ni) }
    }
}

impl JacState for JacBuf {
    fn f(&self, e: usize) -> f64 {
        self.f[e]
    }
    fn j(&self, e: usize, u: usize) -> f64 {
        self.j[e * self.f.len() + u]
    }
    fn fx(&self, e: usize, i: usize) -> f64 {
        self.fx[e * self.input_unit.len() + i]
    }
    fn scale(&self, e: usize) -> f64 {
        self.scale[e]
    }
    fn unit(&self, u: usize) -> f64 {
        self.unit[u]
    }
    fn input_unit(&self, i: usize) -> f64 {
        self.input_unit[i]
    }
}

/// How a mechanism's sizes are known, with the storage of each shape the generic algorithms
/// hold: `n` unknowns (= scalar equations), `ni` inputs, `no` output columns.
pub trait Dims: Copy + fmt::Debug {
    /// A vector of the unknowns' size.
    type Q: Store;
    /// A vector of the inputs' size.
    type X: Store;
    /// A square matrix of the inputs' size.
    type XX: Square;
    /// A kinematic state.
    type Kin: KinState;
    /// Residuals and Jacobians.
    type Jac: JacState;
    /// The number of unknowns.
    fn n(self) -> usize;
    /// The number of inputs.
    fn ni(self) -> usize;
    /// The number of output columns.
    fn no(self) -> usize;
    /// A vector of zeros of the unknowns' size.
    fn q(self) -> Self::Q;
    /// A vector of zeros of the inputs' size.
    fn x(self) -> Self::X;
    /// A square matrix of zeros of the inputs' size.
    fn xx(self) -> Self::XX;
    /// A state of zeros.
    fn kin(self) -> Self::Kin;
    /// The determinant and the smallest pivot ratio of the column-equilibrated full Jacobian
    /// `jac.j` (each column divided by its largest magnitude), as `Lu::factor_cols` gives them.
    fn equilibrated(self, jac: &Self::Jac) -> (f64, f64);
}

/// Sizes known when the mechanism is compiled: `N` unknowns, `NI` inputs, `NO` output columns,
/// in arrays (zero-sized; what every generated mechanism has).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Fixed<const N: usize, const NI: usize, const NO: usize>;

impl<const N: usize, const NI: usize, const NO: usize> Dims for Fixed<N, NI, NO> {
    type Q = [f64; N];
    type X = [f64; NI];
    type XX = [[f64; NI]; NI];
    type Kin = Kin<N, NI, NO>;
    type Jac = Jac<N, NI>;
    #[inline(always)]
    fn n(self) -> usize {
        N
    }
    #[inline(always)]
    fn ni(self) -> usize {
        NI
    }
    #[inline(always)]
    fn no(self) -> usize {
        NO
    }
    #[inline(always)]
    fn q(self) -> [f64; N] {
        [0.0; N]
    }
    #[inline(always)]
    fn x(self) -> [f64; NI] {
        [0.0; NI]
    }
    #[inline(always)]
    fn xx(self) -> [[f64; NI]; NI] {
        [[0.0; NI]; NI]
    }
    #[inline(always)]
    fn kin(self) -> Kin<N, NI, NO> {
        Kin {
            x: [0.0; NI],
            q: [0.0; N],
            dq: [[0.0; NI]; N],
            d2q: [[[0.0; NI]; NI]; N],
            out: [0.0; NO],
            dout: [[0.0; NI]; NO],
            d2out: [[[0.0; NI]; NI]; NO],
            report: SolveReport::direct(),
            health: Health::default(),
        }
    }
    fn equilibrated(self, jac: &Jac<N, NI>) -> (f64, f64) {
        let lu = equilibrated_lu(&jac.j);
        (lu.det(), lu.pivot_ratio())
    }
}

/// The column-equilibrated factorisation of `j`.
fn equilibrated_lu<const N: usize>(j: &[[f64; N]; N]) -> Lu<N> {
    let mut scale = [0.0f64; N];
    for row in j {
        for u in 0..N {
            scale[u] = scale[u].max(row[u].abs());
        }
    }
    Lu::<N>::factor_cols(j, scale)
}

/// Sizes known at run time (a mechanism read from text): the storage is boxed slices, which a
/// sweep allocates once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sizes {
    /// Unknowns (= scalar equations).
    pub n: usize,
    /// Inputs.
    pub ni: usize,
    /// Output columns.
    pub no: usize,
}

impl Dims for Sizes {
    type Q = Heap;
    type X = Heap;
    type XX = Heap2;
    type Kin = KinBuf;
    type Jac = JacBuf;
    fn n(self) -> usize {
        self.n
    }
    fn ni(self) -> usize {
        self.ni
    }
    fn no(self) -> usize {
        self.no
    }
    fn q(self) -> Heap {
        Heap::zeros(self.n)
    }
    fn x(self) -> Heap {
        Heap::zeros(self.ni)
    }
    fn xx(self) -> Heap2 {
        Heap2::zeros(self.ni)
    }
    fn kin(self) -> KinBuf {
        KinBuf::zeros(self)
    }
    fn equilibrated(self, jac: &JacBuf) -> (f64, f64) {
        let n = self.n;
        fn fixed<const K: usize>(j: &[f64]) -> (f64, f64) {
            let mut a = [[0.0; K]; K];
            for (e, row) in a.iter_mut().enumerate() {
                row.copy_from_slice(&j[e * K..(e + 1) * K]);
            }
            let lu = equilibrated_lu(&a);
            (lu.det(), lu.pivot_ratio())
        }
        macro_rules! dispatch {
            ($($k:literal)*) => {
                match n {
                    $($k => return fixed::<$k>(&jac.j),)*
                    _ => {}
                }
            };
        }
        // Up to 12 unknowns the same factorisation as a compiled mechanism's (the runtime's LU
        // of that size, bit for bit); a larger system's comes from nalgebra's LU (partial
        // pivoting too, its roundings not guaranteed the same).
        dispatch!(1 2 3 4 5 6 7 8 9 10 11 12);
        // Larger: nalgebra's LU of the column-equilibrated matrix.
        let mut a = nalgebra::DMatrix::from_fn(n, n, |e, u| jac.j[e * n + u]);
        for c in 0..n {
            // A zero column stays zero (its determinant 0, as the runtime's LU gives), not NaN.
            let big = a.column(c).amax();
            if big > 0.0 {
                a.column_mut(c).unscale_mut(big);
            }
        }
        let lu = a.lu();
        let u = lu.u();
        let pivot = (0..n).map(|k| u[(k, k)].abs()).fold(f64::INFINITY, f64::min);
        let det = lu.determinant();
        (det, if pivot.is_nan() || n == 0 { 0.0 } else { pivot })
    }
}
