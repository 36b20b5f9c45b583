//! A CSV table written row by row, as its rows are made: a long sweep keeps none of them.
//!
//! Every CSV the command writes goes through [`CsvRows`] (or, for `synth`'s with its column of
//! text, writes its numbers as it does): a value that is zero is written `0`,
//! whatever the sign IEEE arithmetic left on it (`-r sin 0` is `-0.0`). [`Number`] writes the
//! bits, `-0`, which read as a value below zero where the analog of a slider at its dead centre
//! is exactly zero, and as another value than the same zero written on standard error
//! (`kinloop dynamics` wrote `mean_torque = 0` there and `-0` into `--flywheel`).

use kinloop_runtime::{Number, Table};
use std::io::{self, Write};

/// A CSV table being written: the header first, then each row as it comes, in the bytes
/// [`Table::write_csv`] writes for the same table (its numbers written as [`Number`] writes
/// them, fields separated by commas, lines ended by `\n`; a number never needs quotes), but for
/// a zero, written without a sign ([`unsigned_zero`]).
pub struct CsvRows<W: Write> {
    out: W,
    /// The line being written, kept to be reused: no allocation per row.
    line: String,
}

impl<W: Write> CsvRows<W> {
    /// Writes the header of `header` (its columns with their units, and its rows if it has
    /// any) to `out`, and returns the writer of the rows that follow.
    pub fn new(mut out: W, header: &Table) -> io::Result<Self> {
        header.write_csv(&mut out)?;
        Ok(CsvRows { out, line: String::new() })
    }

    /// Writes one row, handed to the writer in one piece (a buffered `out` passes it on when
    /// its buffer is full).
    pub fn row(&mut self, values: &[f64]) -> io::Result<()> {
        self.line.clear();
        for (k, v) in values.iter().enumerate() {
            if k > 0 {
                self.line.push(',');
            }
            Number(unsigned_zero(*v)).push_to(&mut self.line);
        }
        self.line.push('\n');
        self.out.write_all(self.line.as_bytes())
    }

    /// Flushes what the writer still holds: the table is written only once this succeeds.
    pub fn finish(mut self) -> io::Result<()> {
        self.out.flush()
    }
}

/// `v`, a negative zero made zero (`-0.0 + 0.0` is `0.0`; any other value is left as it is).
pub fn unsigned_zero(v: f64) -> f64 {
    v + 0.0
}

/// Writes `table` as CSV to `out`, as [`CsvRows`] writes its rows: the bytes of
/// [`Table::write_csv`] but for a zero, written without a sign.
pub fn write_table<W: Write>(out: W, table: &Table) -> io::Result<()> {
    let header = Table { columns: table.columns.clone(), rows: Vec::new(), units: table.units.clone() };
    let mut rows = CsvRows::new(out, &header)?;
    for row in &table.rows {
        rows.row(row)?;
    }
    rows.finish()
}

#[cfg(test)]
mod tests {
    use super::{CsvRows, unsigned_zero, write_table};
    use kinloop_runtime::Table;

    /// Row by row, the bytes of the whole table written at once by the `csv` crate: numbers at
    /// every magnitude and the values that are not finite, one column and several. (A
    /// negative zero is not among them: written `0` here, `-0` there; see below.)
    #[test]
    fn rows_written_one_by_one_are_the_tables_bytes() {
        let values = [0.0, 0.1, -2.5, 150.0, 1e-5, 9.9e-6, 1e16, -1e300, 5e-324, -5e-324, f64::NAN, f64::INFINITY];
        for width in [1, 3] {
            let mut table = Table::new((0..width).map(|k| format!("c{k}")).collect());
            for chunk in values.chunks(width) {
                table.push(chunk.to_vec());
            }
            let table = table.with_units(&[("c0", "mm"), ("c1", "rad")]);
            let mut whole = Vec::new();
            table.write_csv(&mut whole).expect("a table in memory");
            let mut streamed = Vec::new();
            let mut rows = CsvRows::new(&mut streamed, &Table { rows: Vec::new(), ..table.clone() }).expect("header");
            for row in &table.rows {
                rows.row(row).expect("a row in memory");
            }
            rows.finish().expect("flushed");
            assert_eq!(String::from_utf8_lossy(&streamed), String::from_utf8_lossy(&whole));
        }
    }

    /// A zero is written `0` whatever its sign, by the rows and by a whole table alike; the
    /// smallest values beside it keep theirs.
    #[test]
    fn a_negative_zero_is_written_as_zero() {
        assert_eq!(unsigned_zero(-0.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(unsigned_zero(-5e-324), -5e-324);
        let mut table = Table::new(vec!["x".into(), "v".into()]);
        table.push(vec![-0.0, -5e-324]);
        table.push(vec![0.0, -0.0]);
        let table = table.with_units(&[("x", "mm")]);
        let mut written = Vec::new();
        write_table(&mut written, &table).expect("a table in memory");
        assert_eq!(String::from_utf8_lossy(&written), "x [mm],v\n0,-5e-324\n0,0\n");
    }
}
