//! Typed handles of a mechanism's columns (an input, an unknown or an output column), as the
//! analysis helpers take them.
//!
//! `mechanism!` generates one handle per column of every mechanism, reached through the
//! constant `Name::COL` (`FourBar::COL.beta`, `FourBar::COL.cp.x`: the same paths as the
//! state's `s.q.beta`, `s.out.cp.x`). A handle carries its mechanism in its type, so a column
//! of one mechanism cannot be given to a [`Sampled`](super::Sampled) of another, and a
//! misspelled column is a compile error. [`Column::named`] is the dynamic fallback, for names
//! that only exist at run time (a command line, a configuration file).

use crate::dims::{Dims, KinState};
use crate::error::Error;
use crate::kin::Kin;
use crate::kinds::QuantityKind;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::{Compiled, Kernel};
use std::fmt;
use std::marker::PhantomData;

/// Which flat array a column lives in, and its index there (declaration order).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ColumnIndex {
    /// Index into `Mechanism::INPUTS` (the value of an input, its own analog is 1).
    Input(usize),
    /// Index into `Mechanism::UNKNOWNS`.
    Unknown(usize),
    /// Index into `Mechanism::OUTPUTS` (`p.x`, `p.y` for a point `p`, or a scalar output).
    Output(usize),
}

/// An input, unknown or output column of mechanism `M`: generated as `Name::COL.field`, or
/// looked up by name at run time with [`Column::named`].
pub struct Column<M> {
    index: ColumnIndex,
    name: &'static str,
    _m: PhantomData<fn() -> M>,
}

impl<M> crate::table::ColumnKey for Column<M> {
    fn column_name(&self) -> &str {
        self.name
    }
}

// Written by hand: derives would require `M: Clone`, `M: Debug`, ... of the mechanism.
impl<M> Clone for Column<M> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M> Copy for Column<M> {}
impl<M> PartialEq for Column<M> {
    fn eq(&self, other: &Self) -> bool {
        self.index == other.index
    }
}
impl<M> Eq for Column<M> {}
impl<M> fmt::Debug for Column<M> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Column({}: {:?})", self.name, self.index)
    }
}

/// The column's name (`beta`, `cp.x`).
impl<M> fmt::Display for Column<M> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name)
    }
}

impl<M> Column<M> {
    /// For the expansion of `mechanism!` only: the index is trusted to belong to `M`.
    #[doc(hidden)]
    pub const fn __generated(index: ColumnIndex, name: &'static str) -> Self {
        Column { index, name, _m: PhantomData }
    }

    /// The column's flat array and index.
    pub fn index(self) -> ColumnIndex {
        self.index
    }

    /// The column's name as in the flat name lists (`"beta"`, `"cp.x"`).
    pub fn name(self) -> &'static str {
        self.name
    }

    /// The input, unknown or output column called `name` (`"beta"`, `"cp.x"`): the dynamic
    /// fallback of the generated `Name::COL.beta`, for names known only at run time. A name
    /// that is none of them is an [`Error::InvalidArgument`] listing the columns.
    ///
    /// ```ignore
    /// let beta = Column::<FourBar>::named("beta")?;
    /// assert_eq!(beta, FourBar::COL.beta);
    /// ```
    pub fn named<const N: usize, const NI: usize, const NO: usize>(name: &str) -> Result<Self, Error>
    where
        M: Mechanism<N, NI, NO>,
    {
        let find = |names: &[&'static str]| names.iter().position(|n| *n == name);
        let index = find(&M::INPUTS)
            .map(ColumnIndex::Input)
            .or_else(|| find(&M::UNKNOWNS).map(ColumnIndex::Unknown))
            .or_else(|| find(&M::OUTPUTS).map(ColumnIndex::Output));
        match index {
            Some(index) => Ok(Column::__generated(index, Self::name_at::<N, NI, NO>(index))),
            None => {
                Err(Error::InvalidArgument(no_column_message(name, M::NAME, [&M::INPUTS, &M::UNKNOWNS, &M::OUTPUTS])))
            }
        }
    }

    /// The name of a column index of `M` (`"?"` outside its ranges).
    fn name_at<const N: usize, const NI: usize, const NO: usize>(index: ColumnIndex) -> &'static str
    where
        M: Mechanism<N, NI, NO>,
    {
        let name = match index {
            ColumnIndex::Input(i) => M::INPUTS.get(i),
            ColumnIndex::Unknown(u) => M::UNKNOWNS.get(u),
            ColumnIndex::Output(o) => M::OUTPUTS.get(o),
        };
        name.copied().unwrap_or("?")
    }

    /// Checks that the index lies within `M`'s columns (always so for generated handles and
    /// [`Column::named`]): helpers call it before indexing a state.
    pub(crate) fn check<const N: usize, const NI: usize, const NO: usize>(self) -> Result<Self, Error>
    where
        M: Mechanism<N, NI, NO>,
    {
        let ok = match self.index {
            ColumnIndex::Input(i) => i < NI,
            ColumnIndex::Unknown(u) => u < N,
            ColumnIndex::Output(o) => o < NO,
        };
        if ok {
            Ok(self)
        } else {
            Err(Error::InvalidArgument(format!("column {self:?} does not exist in `{}`", M::NAME)))
        }
    }

    /// The column's value in a state.
    pub fn value<const N: usize, const NI: usize, const NO: usize>(self, k: &Kin<N, NI, NO>) -> f64 {
        match self.index {
            ColumnIndex::Input(i) => k.x[i],
            ColumnIndex::Unknown(u) => k.q[u],
            ColumnIndex::Output(o) => k.out[o],
        }
    }

    /// Its velocity analogs in a state: the derivative with respect to each input.
    pub fn gradient<const N: usize, const NI: usize, const NO: usize>(self, k: &Kin<N, NI, NO>) -> [f64; NI] {
        match self.index {
            ColumnIndex::Input(i) => std::array::from_fn(|j| if i == j { 1.0 } else { 0.0 }),
            ColumnIndex::Unknown(u) => k.dq[u],
            ColumnIndex::Output(o) => k.dout[o],
        }
    }

    /// Its acceleration analogs in a state: the second derivative with respect to each pair of
    /// inputs (an input's own are zero).
    pub fn hessian<const N: usize, const NI: usize, const NO: usize>(self, k: &Kin<N, NI, NO>) -> [[f64; NI]; NI] {
        match self.index {
            ColumnIndex::Input(_) => [[0.0; NI]; NI],
            ColumnIndex::Unknown(u) => k.d2q[u],
            ColumnIndex::Output(o) => k.d2out[o],
        }
    }

    /// The column along a straight path through state `k` at path parameter `s`, the inputs
    /// moving by `dir` per unit of `s`: value, `d/ds = g . dir` and `d2/ds2 = dir . H . dir`
    /// (a straight path has no curvature term).
    pub fn jet_along<const N: usize, const NI: usize, const NO: usize>(
        self,
        k: &Kin<N, NI, NO>,
        s: f64,
        dir: &[f64; NI],
    ) -> super::Jet {
        jet_along(self.index, k, s, dir)
    }

    /// The column's value and analogs in a single-input state, as a function of the input.
    pub fn jet<const N: usize, const NO: usize>(self, k: &Kin<N, 1, NO>) -> super::Jet {
        jet_of_input(self.index, k)
    }
}

/// The column `index` in a single-input state `k`, as a function of the input.
pub(crate) fn jet_of_input<S: KinState>(index: ColumnIndex, k: &S) -> super::Jet {
    jet_along(index, k, k.x()[0], &[1.0])
}

/// The column `index` along a straight path through state `k` at path parameter `s`, the inputs
/// moving by `dir` per unit of `s` (see [`Column::jet_along`]): the one computation of a
/// column's jet, whatever the state's storage.
pub(crate) fn jet_along<S: KinState>(index: ColumnIndex, k: &S, s: f64, dir: &[f64]) -> super::Jet {
    // An input's gradient is the unit vector, its Hessian zero.
    match index {
        ColumnIndex::Input(i) => contract(k.x()[i], |j| if i == j { 1.0 } else { 0.0 }, |_, _| 0.0, s, dir),
        ColumnIndex::Unknown(u) => contract(k.q()[u], |i| k.dq(u)[i], |i, j| k.d2q(u, i, j), s, dir),
        ColumnIndex::Output(o) => contract(k.out()[o], |i| k.dout(o)[i], |i, j| k.d2out(o, i, j), s, dir),
    }
}

/// The jet of a quantity of value `value`, gradient `g` and Hessian `h` along `dir`.
#[inline(always)]
fn contract(value: f64, g: impl Fn(usize) -> f64, h: impl Fn(usize, usize) -> f64, s: f64, dir: &[f64]) -> super::Jet {
    let ni = dir.len();
    let d1 = (0..ni).map(|i| g(i) * dir[i]).sum();
    let d2 = (0..ni).map(|i| (0..ni).map(|j| h(i, j) * dir[j]).sum::<f64>() * dir[i]).sum();
    super::Jet { x: s, value, d1, d2 }
}

/// A column as the analyses over a kernel `K` take it: the generated typed handle
/// (`Name::COL.beta`, for a compiled mechanism), a name known at run time (`"beta"`, `"cp.x"`,
/// for any kernel, a run-time model's included), or a [`ColumnIndex`].
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not a column of the mechanism `{K}` samples",
    label = "not a column of the sampled mechanism",
    note = "a column is a handle of the sampled mechanism (`Name::COL.field`), a name (`\"field\"`) or a `ColumnIndex`; `Column::named(..)` gives a `Result`: take its column with `?`"
)]
pub trait ColumnOf<K: Kernel>: Copy {
    /// The column's flat array and index in `k`; an [`Error::InvalidArgument`] for a column
    /// `k` does not have (naming its columns).
    fn resolve(self, k: &K) -> Result<ColumnIndex, Error>;
}

impl<M, const N: usize, const NI: usize, const NO: usize> ColumnOf<Compiled<'_, M, N, NI, NO>> for Column<M>
where
    M: Mechanism<N, NI, NO>,
{
    #[inline]
    fn resolve(self, _: &Compiled<'_, M, N, NI, NO>) -> Result<ColumnIndex, Error> {
        self.check::<N, NI, NO>().map(Column::index)
    }
}

impl<K: Kernel> ColumnOf<K> for ColumnIndex {
    fn resolve(self, k: &K) -> Result<ColumnIndex, Error> {
        let d = k.dims();
        let ok = match self {
            ColumnIndex::Input(i) => i < d.ni(),
            ColumnIndex::Unknown(u) => u < d.n(),
            ColumnIndex::Output(o) => o < d.no(),
        };
        if ok {
            Ok(self)
        } else {
            Err(Error::InvalidArgument(format!("column {self:?} does not exist in `{}`", k.name())))
        }
    }
}

/// Found by comparing the kernel's names in place: a resolved name allocates nothing (a
/// sampled analysis may resolve a column per call); only the error lists the columns.
impl<K: Kernel> ColumnOf<K> for &str {
    fn resolve(self, k: &K) -> Result<ColumnIndex, Error> {
        let d = k.dims();
        let found = (0..d.ni()).position(|i| k.input_name(i) == self).map(ColumnIndex::Input);
        found
            .or_else(|| (0..d.n()).position(|u| k.unknown_name(u) == self).map(ColumnIndex::Unknown))
            .or_else(|| (0..d.no()).position(|o| k.output_name(o) == self).map(ColumnIndex::Output))
            .ok_or_else(|| no_column(self, k))
    }
}

/// The error of a name that is no column of `k`, listing its columns.
#[cold]
#[inline(never)]
fn no_column<K: Kernel>(name: &str, k: &K) -> Error {
    let d = k.dims();
    let inputs: Vec<&str> = (0..d.ni()).map(|i| k.input_name(i)).collect();
    let unknowns: Vec<&str> = (0..d.n()).map(|u| k.unknown_name(u)).collect();
    let outputs: Vec<&str> = (0..d.no()).map(|o| k.output_name(o)).collect();
    Error::InvalidArgument(no_column_message(name, k.name(), [&inputs, &unknowns, &outputs]))
}

/// The message of a name that is no column of mechanism `mechanism`, listing its `[inputs,
/// unknowns, outputs]` (`none` for a group without any: a list left empty read as cut off); a
/// point's name (`pc`) is told its two columns (`pc.x` and `pc.y`).
fn no_column_message(name: &str, mechanism: &str, [inputs, unknowns, outputs]: [&[&str]; 3]) -> String {
    let list = |names: &[&str]| if names.is_empty() { "none".to_string() } else { names.join(", ") };
    let mut message = format!(
        "`{name}` is no column of `{mechanism}`: inputs {}; unknowns {}; outputs {}",
        list(inputs),
        list(unknowns),
        list(outputs)
    );
    let (x, y) = (format!("{name}.x"), format!("{name}.y"));
    if outputs.contains(&x.as_str()) && outputs.contains(&y.as_str()) {
        message.push_str(&format!(" (`{name}` is a point: its columns are `{x}` and `{y}`)"));
    }
    message
}

/// The kind of quantity of column `index` of `k`.
pub(crate) fn column_kind<K: Kernel>(k: &K, index: ColumnIndex) -> QuantityKind {
    match index {
        ColumnIndex::Unknown(u) => k.unknown_kind(u),
        ColumnIndex::Output(o) => k.output_kind(o),
        ColumnIndex::Input(i) => k.input_kind(i),
    }
}

/// The name of column `index` of `k` (`"?"` outside its ranges).
pub(crate) fn column_name<K: Kernel>(k: &K, index: ColumnIndex) -> &str {
    let d = k.dims();
    match index {
        ColumnIndex::Input(i) if i < d.ni() => k.input_name(i),
        ColumnIndex::Unknown(u) if u < d.n() => k.unknown_name(u),
        ColumnIndex::Output(o) if o < d.no() => k.output_name(o),
        _ => "?",
    }
}
