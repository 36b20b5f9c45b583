//! What the flat data of a mechanism can do knowing the mechanism: the true motion of a state
//! checked with the names of its unknowns and outputs ([`Kin::checked_motion`]), and tables of
//! states with the mechanism's column names and units ([`Table::from_states`]).
//!
//! [`Kin`] and [`Table`] are plain data defined below the [`Mechanism`] trait; these methods,
//! generic over a mechanism, are theirs (called as `kin.checked_motion::<M>(..)`,
//! `Table::from_states::<M, _, _, _>(..)`) but defined here, on the trait's side.

use crate::dims::Dims;
use crate::error::{Computed, Error};
use crate::events::Location;
use crate::kin::{FlatMotion, Kin};
use crate::kinds::QuantityKind;
use crate::mechanism::Mechanism;
use crate::mechanism::kernel::Kernel;
use crate::table::Table;

impl<const N: usize, const NI: usize, const NO: usize> Kin<N, NI, NO> {
    /// [`Kin::motion`], checked: an `Error::Overflow` naming the first unknown or output
    /// whose velocity or acceleration is not finite (the analogs are finite, so only huge
    /// speeds or accelerations can cause it).
    pub fn checked_motion<M: Mechanism<N, NI, NO>>(
        &self,
        omega: &[f64; NI],
        eps: &[f64; NI],
    ) -> Result<FlatMotion<N, NO>, Error> {
        let m = self.motion(omega, eps);
        let bad = |v: &[f64]| v.iter().position(|x| !x.is_finite());
        let found = [
            (Computed::Velocity, bad(&m.qdot), &M::UNKNOWNS[..]),
            (Computed::Acceleration, bad(&m.qddot), &M::UNKNOWNS[..]),
            (Computed::OutputVelocity, bad(&m.out_dot), &M::OUTPUTS[..]),
            (Computed::OutputAcceleration, bad(&m.out_ddot), &M::OUTPUTS[..]),
        ]
        .into_iter()
        .find_map(|(what, index, names)| index.map(|i| (what, names.get(i).copied().unwrap_or("?"))));
        match found {
            None => Ok(m),
            Some((what, name)) => Err(Error::Overflow {
                what,
                name: name.into(),
                at: Location::boxed(M::NAME, &M::INPUTS, &self.x, None),
            }),
        }
    }
}

impl Table {
    /// The table with the units of mechanism `M`'s columns as `mechanism!` inferred them
    /// ([`Mechanism::INPUT_KINDS`], [`Mechanism::UNKNOWN_KINDS`], [`Mechanism::OUTPUT_KINDS`]):
    /// angles in `rad`, lengths in [`LENGTH_UNIT`](crate::LENGTH_UNIT), their analogs the
    /// quotients. An input of a kind not inferred (a time `t`) is in `unit of t`, so that the
    /// analogs by it say what they are per (`d(psi)/d(t)` in `rad/unit of t`); other columns
    /// of a kind not inferred get none.
    ///
    /// ```
    /// use kinloop_runtime::{QuantityKind, Table};
    /// let mut t = Table::new(vec!["t".into(), "psi".into(), "d(psi)/d(t)".into()]);
    /// t.push(vec![0.5, 1.0, -0.25]);
    /// let t = t.with_kinds(&[("t", QuantityKind::Other)], &[("psi", QuantityKind::Angle)]);
    /// assert_eq!(t.unit("t"), Some("unit of t"));
    /// assert_eq!(t.unit("d(psi)/d(t)"), Some("rad/unit of t"));
    /// ```
    pub fn with_units_of<M, const N: usize, const NI: usize, const NO: usize>(self) -> Self
    where
        M: Mechanism<N, NI, NO>,
    {
        let inputs: Vec<_> = M::INPUTS.iter().copied().zip(M::INPUT_KINDS).collect();
        let unknowns = M::UNKNOWNS.iter().copied().zip(M::UNKNOWN_KINDS);
        let outputs = M::OUTPUTS.iter().copied().zip(M::OUTPUT_KINDS);
        let rest: Vec<_> = unknowns.chain(outputs).collect();
        self.with_kinds(&inputs, &rest)
    }

    /// The table with the units of quantities of known kinds: `inputs` and the `rest`
    /// (unknowns and outputs), each `(name, kind)`, by the rule of [`Table::with_units_of`].
    pub fn with_kinds(self, inputs: &[(&str, QuantityKind)], rest: &[(&str, QuantityKind)]) -> Self {
        let units: Vec<(&str, std::borrow::Cow<str>)> = inputs
            .iter()
            .map(|(n, k)| (*n, k.input_unit(n)))
            .chain(rest.iter().map(|(n, k)| (*n, k.unit().into())))
            .collect();
        let base: Vec<(&str, &str)> = units.iter().map(|(n, u)| (*n, u.as_ref())).collect();
        self.with_units(&base)
    }

    /// The columns of a kinematic state of mechanism `M`: inputs, unknowns, their first and
    /// second analogs (`d(u)/d(i)`, `d2(u)/d(i)d(j)`), outputs and their analogs.
    pub fn kin_columns<M, const N: usize, const NI: usize, const NO: usize>() -> Vec<String>
    where
        M: Mechanism<N, NI, NO>,
    {
        columns(&M::INPUTS, &M::UNKNOWNS, &M::OUTPUTS)
    }

    /// The columns of a kinematic state of kernel `k` (see [`Table::kin_columns`]): a compiled
    /// mechanism's, or a mechanism's read at run time.
    pub fn kernel_columns<K: Kernel>(k: &K) -> Vec<String> {
        let d = k.dims();
        let inputs: Vec<&str> = (0..d.ni()).map(|i| k.input_name(i)).collect();
        let unknowns: Vec<&str> = (0..d.n()).map(|u| k.unknown_name(u)).collect();
        let outputs: Vec<&str> = (0..d.no()).map(|o| k.output_name(o)).collect();
        columns(&inputs, &unknowns, &outputs)
    }

    /// The table with the units of kernel `k`'s columns (see [`Table::with_units_of`]).
    pub fn with_kernel_units<K: Kernel>(self, k: &K) -> Self {
        let d = k.dims();
        let inputs: Vec<_> = (0..d.ni()).map(|i| (k.input_name(i), k.input_kind(i))).collect();
        let unknowns = (0..d.n()).map(|u| (k.unknown_name(u), k.unknown_kind(u)));
        let outputs = (0..d.no()).map(|o| (k.output_name(o), k.output_kind(o)));
        let rest: Vec<_> = unknowns.chain(outputs).collect();
        self.with_kinds(&inputs, &rest)
    }

    /// A table of kinematic states of mechanism `M`, with the units inferred by `mechanism!` in
    /// its header (see [`Table::with_units_of`]; [`Table::with_length_unit`] names the unit of
    /// length, [`Table::with_units`] overrides any).
    pub fn from_states<'a, M, const N: usize, const NI: usize, const NO: usize>(
        states: impl IntoIterator<Item = &'a Kin<N, NI, NO>>,
    ) -> Self
    where
        M: Mechanism<N, NI, NO>,
    {
        let mut t = Table::new(Self::kin_columns::<M, N, NI, NO>());
        for k in states {
            t.push(Self::kin_row(k));
        }
        t.with_units_of::<M, N, NI, NO>()
    }
}

/// The columns of a kinematic state: inputs, unknowns, their first and second analogs
/// (`d(u)/d(i)`, `d2(u)/d(i)d(j)`), outputs and their analogs.
fn columns(inputs: &[&str], unknowns: &[&str], outputs: &[&str]) -> Vec<String> {
    let mut c: Vec<String> = inputs.iter().map(|s| s.to_string()).collect();
    for names in [unknowns, outputs] {
        c.extend(names.iter().map(|s| s.to_string()));
        for n in names {
            for i in inputs {
                c.push(format!("d({n})/d({i})"));
            }
        }
        for n in names {
            for (a, i) in inputs.iter().enumerate() {
                for j in &inputs[a..] {
                    c.push(if i == j { format!("d2({n})/d({i})^2") } else { format!("d2({n})/d({i})d({j})") });
                }
            }
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::columns;
    use crate::Table;
    use crate::kin::{Health, Kin};
    use crate::solvers::newton::SolveReport;

    /// Every value of a state of two inputs lands under the column that names it: each value is
    /// coded by its indices, and the expected code is read back from the column's own name.
    #[test]
    fn a_two_input_row_puts_each_value_under_its_name() {
        let code = |base: f64, u: usize, i: usize, j: usize| base + 100.0 * u as f64 + 10.0 * i as f64 + j as f64;
        let k = Kin::<2, 2, 1> {
            x: [1.0, 2.0],
            q: [code(1000.0, 0, 0, 0), code(1000.0, 1, 0, 0)],
            dq: std::array::from_fn(|u| std::array::from_fn(|i| code(2000.0, u, i, 0))),
            d2q: std::array::from_fn(|u| std::array::from_fn(|i| std::array::from_fn(|j| code(3000.0, u, i, j)))),
            out: [code(5000.0, 0, 0, 0)],
            dout: [std::array::from_fn(|i| code(6000.0, 0, i, 0))],
            d2out: [std::array::from_fn(|i| std::array::from_fn(|j| code(7000.0, 0, i, j)))],
            report: SolveReport::direct(),
            health: Health::default(),
        };
        let (inputs, unknowns, outputs) = (["a", "b"], ["p", "q"], ["o"]);
        let names = columns(&inputs, &unknowns, &outputs);
        let row = Table::kin_row(&k);
        assert_eq!(names.len(), row.len());
        let input = |s: &str| inputs.iter().position(|n| *n == s).unwrap();
        for (name, value) in names.iter().zip(&row) {
            let expected = if let Some(i) = inputs.iter().position(|n| n == name) {
                k.x[i]
            } else if let Some(rest) = name.strip_prefix("d2(") {
                // `d2(n)/d(i)^2` or `d2(n)/d(i)d(j)`.
                let (n, rest) = rest.split_once(")/d(").unwrap();
                let (i, j) = match rest.strip_suffix(")^2") {
                    Some(i) => (input(i), input(i)),
                    None => {
                        let (i, j) = rest.trim_end_matches(')').split_once(")d(").unwrap();
                        (input(i), input(j))
                    }
                };
                match unknowns.iter().position(|u| *u == n) {
                    Some(u) => code(3000.0, u, i, j),
                    None => code(7000.0, 0, i, j),
                }
            } else if let Some(rest) = name.strip_prefix("d(") {
                let (n, i) = rest.trim_end_matches(')').split_once(")/d(").unwrap();
                match unknowns.iter().position(|u| *u == n) {
                    Some(u) => code(2000.0, u, input(i), 0),
                    None => code(6000.0, 0, input(i), 0),
                }
            } else {
                match unknowns.iter().position(|u| u == name) {
                    Some(u) => code(1000.0, u, 0, 0),
                    None => code(5000.0, 0, 0, 0),
                }
            };
            assert_eq!(*value, expected, "column {name}");
        }
    }
}
