//! A table of kinematic states with named columns, and its CSV export.

use crate::kin::Kin;
use crate::mechanism::Mechanism;
use std::io::{self, Write};
use std::path::Path;

/// Rows of numbers under named columns (one row per input value of a sweep).
///
/// ```
/// use kinloop_runtime::Table;
/// let mut t = Table::new(vec!["t".into(), "x".into()]);
/// t.push(vec![0.0, 1.5]);
/// t.push(vec![0.1, 1.25]);
/// assert_eq!(t.column("x").unwrap(), vec![1.5, 1.25]);
/// let mut csv = Vec::new();
/// t.write_csv(&mut csv).unwrap();
/// assert_eq!(String::from_utf8(csv).unwrap(), "t,x\n0,1.5\n0.1,1.25\n");
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Table {
    /// Column names.
    pub columns: Vec<String>,
    /// Rows, each as long as `columns`.
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// An empty table with these columns.
    pub fn new(columns: Vec<String>) -> Self {
        Table { columns, rows: Vec::new() }
    }

    /// Appends a row (it must have one value per column).
    pub fn push(&mut self, row: Vec<f64>) {
        debug_assert_eq!(row.len(), self.columns.len());
        self.rows.push(row);
    }

    /// Index of a column by name.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }

    /// A column's values by name.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let k = self.index(name)?;
        Some(self.rows.iter().map(|r| r.get(k).copied().unwrap_or(f64::NAN)).collect())
    }

    /// Writes the table as CSV (header line, then one line per row; shortest round-trip
    /// formatting of every value).
    pub fn write_csv(&self, mut w: impl Write) -> io::Result<()> {
        writeln!(w, "{}", self.columns.iter().map(|c| csv_field(c)).collect::<Vec<_>>().join(","))?;
        for row in &self.rows {
            let line = row.iter().map(|v| v.to_string()).collect::<Vec<_>>().join(",");
            writeln!(w, "{line}")?;
        }
        Ok(())
    }

    /// Writes the table as a CSV file, creating missing parent directories.
    pub fn save_csv(&self, path: impl AsRef<Path>) -> io::Result<()> {
        let path = path.as_ref();
        if let Some(dir) = path.parent()
            && !dir.as_os_str().is_empty()
        {
            std::fs::create_dir_all(dir)?;
        }
        let file = std::fs::File::create(path)?;
        self.write_csv(io::BufWriter::new(file))
    }

    /// The columns of a kinematic state of mechanism `M`: inputs, unknowns, their first and
    /// second analogs (`d(u)/d(i)`, `d2(u)/d(i)d(j)`), outputs and their analogs.
    pub fn kin_columns<M, const N: usize, const NI: usize, const NO: usize>() -> Vec<String>
    where
        M: Mechanism<N, NI, NO>,
    {
        let mut c: Vec<String> = M::INPUTS.iter().map(|s| s.to_string()).collect();
        let groups: [&[&str]; 2] = [&M::UNKNOWNS, &M::OUTPUTS];
        for names in groups {
            c.extend(names.iter().map(|s| s.to_string()));
            for n in names {
                for i in M::INPUTS {
                    c.push(format!("d({n})/d({i})"));
                }
            }
            for n in names {
                for (a, i) in M::INPUTS.iter().enumerate() {
                    for j in &M::INPUTS[a..] {
                        c.push(if i == j { format!("d2({n})/d({i})^2") } else { format!("d2({n})/d({i})d({j})") });
                    }
                }
            }
        }
        c
    }

    /// One row in the order of [`Table::kin_columns`].
    pub fn kin_row<const N: usize, const NI: usize, const NO: usize>(k: &Kin<N, NI, NO>) -> Vec<f64> {
        let mut r: Vec<f64> = k.x.to_vec();
        r.extend(k.q);
        r.extend(k.dq.iter().flatten());
        for u in &k.d2q {
            for a in 0..NI {
                r.extend(&u[a][a..]);
            }
        }
        r.extend(k.out);
        r.extend(k.dout.iter().flatten());
        for o in &k.d2out {
            for a in 0..NI {
                r.extend(&o[a][a..]);
            }
        }
        r
    }

    /// A table of kinematic states of mechanism `M`.
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
        t
    }
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) { format!("\"{}\"", s.replace('"', "\"\"")) } else { s.to_string() }
}
