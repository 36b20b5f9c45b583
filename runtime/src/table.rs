//! A table of kinematic states with named columns and units, and its CSV export and import.
//!
//! Plain data: the tables of a mechanism's states, with its column names and units
//! ([`Table::from_states`], [`Table::kin_columns`], [`Table::with_units_of`]), are built with the
//! [`Mechanism`](crate::Mechanism) trait, above this module.

use crate::kin::Kin;
use crate::number::{Count, Number};
use crate::table_units;
use std::collections::VecDeque;
use std::io::{self, Write};
use std::path::Path;

/// What names a column of a [`Table`]: a mechanism's typed column (`Name::COL.beta`, checked
/// by the compiler) or, for a lookup decided at run time, its name as a string.
pub trait ColumnKey {
    /// The column's name in a table's header (without its unit).
    fn column_name(&self) -> &str;
}

impl ColumnKey for &str {
    fn column_name(&self) -> &str {
        self
    }
}

impl ColumnKey for String {
    fn column_name(&self) -> &str {
        self
    }
}

impl ColumnKey for &String {
    fn column_name(&self) -> &str {
        self
    }
}

/// Rows of numbers under named columns (one row per input value of a sweep), with optional
/// units written into the CSV header (`phi [rad]`, `x_c [mm]`, `d(x_c)/d(phi) [mm/rad]`).
/// Angles are always in radians.
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
///
/// // Units of the base quantities; the analog columns get theirs from them.
/// let mut s = Table::new(vec!["phi".into(), "x_c".into(), "d(x_c)/d(phi)".into()]);
/// s.push(vec![0.5, 1.0, -0.25]);
/// let s = s.with_units(&[("phi", "rad"), ("x_c", "mm")]);
/// let mut csv = Vec::new();
/// s.write_csv(&mut csv).unwrap();
/// assert!(String::from_utf8(csv.clone()).unwrap().starts_with("phi [rad],x_c [mm],d(x_c)/d(phi) [mm/rad]\n"));
/// assert_eq!(Table::read_csv(&csv[..]).unwrap(), s);
/// ```
///
/// With the feature `serde` a table reads back only with every row as long as `columns`, no
/// more units than columns and no column name twice (an error says which row, how many units
/// or which name), as [`Table::push`] keeps it and [`Table::read_csv`] reads it. JSON holds
/// no NaN nor infinity: a table writes them there as the strings `"NaN"`, `"inf"` and
/// `"-inf"`, which read back as they were (as does `null`, read as NaN); a format that holds
/// them keeps them. serde_json reads every number back to the bit only with its
/// feature `float_roundtrip`: without it, its parser may read the last bit of some numbers
/// differently.
///
/// Two tables are equal (`==`) when their columns, rows and units are, a missing unit equal to
/// `""` (none), as [`Table::unit`] reads it: a table of fewer units than columns equals what
/// its CSV reads back as. The rows compare as numbers (`-0.0 == 0.0`, and NaN equals nothing).
#[derive(Clone, Debug, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize), serde(try_from = "TableRepr"))]
pub struct Table {
    /// Column names.
    pub columns: Vec<String>,
    /// Rows, each as long as `columns`.
    #[cfg_attr(feature = "serde", serde(serialize_with = "crate::floats_serde::serialize_rows"))]
    pub rows: Vec<Vec<f64>>,
    /// Unit of each column (`""` for none; a missing entry is none, and there are at most as
    /// many as columns: [`Table::write_csv`] refuses more), written into the CSV header as
    /// `name [unit]`. A table read ([`Table::read_csv`], or serde) has one per column, `""`
    /// where none was written.
    pub units: Vec<String>,
}

/// A [`Table`] as read by serde, before its shape is checked (its `TryFrom`): a ragged
/// row read unchecked would be missing values, NaN in [`Table::column`], with no error.
#[cfg(feature = "serde")]
#[derive(serde::Deserialize)]
struct TableRepr {
    columns: Vec<String>,
    #[serde(with = "crate::floats_serde")]
    rows: Vec<Vec<f64>>,
    // Tables written before the units were kept have none.
    #[serde(default)]
    units: Vec<String>,
}

#[cfg(feature = "serde")]
impl TryFrom<TableRepr> for Table {
    type Error = String;
    fn try_from(t: TableRepr) -> Result<Table, String> {
        let width = t.columns.len();
        if let Some((k, row)) = t.rows.iter().enumerate().find(|(_, r)| r.len() != width) {
            let (values, columns) = (Count(row.len(), "value"), Count(width, "column"));
            return Err(format!("row {} of the table has {values} for {columns}", k + 1));
        }
        if t.units.len() > width {
            return Err(format!("the table has {} for {}", Count(t.units.len(), "unit"), Count(width, "column")));
        }
        // As `read_csv` refuses it: `Table::column` would find the first alone.
        if let Some((name, j, k)) = repeated(&t.columns) {
            return Err(format!("the column name `{name}` appears twice (columns {j} and {k})"));
        }
        // One unit per column, as a table read from CSV has: a missing one is none.
        let mut units = t.units;
        units.resize(width, String::new());
        Ok(Table { columns: t.columns, rows: t.rows, units })
    }
}

impl PartialEq for Table {
    /// Columns, rows and units alike, a missing unit taken as `""`: the header of
    /// [`Table::write_csv`] writes it as none, which reads back as `""`, and the table read
    /// back is the same table.
    fn eq(&self, other: &Table) -> bool {
        fn unit(units: &[String], k: usize) -> &str {
            units.get(k).map_or("", String::as_str)
        }
        let units = self.units.len().max(other.units.len());
        self.columns == other.columns
            && self.rows == other.rows
            && (0..units).all(|k| unit(&self.units, k) == unit(&other.units, k))
    }
}

/// A CSV reader's error as an `io::Error`: a failure to read keeps its own kind, a malformed
/// input (a ragged row, text that is not UTF-8) is `InvalidData`, as a field that is not a
/// number is (the csv crate's own conversion makes them all `Other`).
fn csv_error(e: csv::Error) -> io::Error {
    if !e.is_io_error() {
        return io::Error::new(io::ErrorKind::InvalidData, e.to_string());
    }
    match e.into_kind() {
        csv::ErrorKind::Io(e) => e,
        kind => io::Error::new(io::ErrorKind::InvalidData, format!("{kind:?}")),
    }
}

/// The `InvalidData` error of a field that is not a number, on line `line` of the file under
/// `column`: it quotes the field, or says that it is empty (a value missing, or a column of
/// text with nothing in this row: an empty field quoted read as a misprint), and that a table
/// holds numbers alone.
fn not_a_number(line: usize, field: &str, column: &str) -> io::Error {
    let what = match field.trim() {
        "" => "is empty".to_string(),
        _ => format!("holds `{field}`"),
    };
    let message = format!(
        "CSV line {line}: column `{column}` {what}, which is not a number: a table holds numbers alone (NaN where a \
         value is not known), and reads no column of text"
    );
    io::Error::new(io::ErrorKind::InvalidData, message)
}

/// A reader that notes where the lines of what it reads end, so that an error can name the
/// line of a byte offset as an editor numbers it: the csv crate's own line count of a record
/// does not count the blank lines before it (a field on line 6 after blank lines 2, 4 and 5
/// was on its "line 4").
///
/// The line ends before the record being read are only counted ([`Lines::settle`]): it holds
/// the offsets of those past its start alone, within what the csv crate reads ahead (its
/// buffer, 8 KiB) and the record's own lines. It held every line end of the file, eight bytes
/// a line, until the whole table was read.
struct Lines<R> {
    inner: R,
    /// The bytes read so far.
    read: u64,
    /// The line ends before the offset last settled, counted.
    before: u64,
    /// The offsets of the line ends read past that offset, in order: an LF, or a CR alone (see
    /// [`line_ends`]).
    ends: VecDeque<u64>,
    /// A CR that ended the last read: a line end of its own unless the next read starts with
    /// an LF (a CRLF split between two reads, whose end is its LF).
    cr: Option<u64>,
}

impl<R> Lines<R> {
    fn new(inner: R) -> Self {
        Lines { inner, read: 0, before: 0, ends: VecDeque::new(), cr: None }
    }

    /// Counts the line ends before `offset` and forgets where they are: no line asked for
    /// after this lies before it (each record read starts where the last ended).
    fn settle(&mut self, offset: u64) {
        while self.ends.front().is_some_and(|&end| end < offset) {
            self.ends.pop_front();
            self.before += 1;
        }
    }

    /// The line (from 1) that the byte at `offset` is on, among those read; `offset` not
    /// before the offset last settled. (A CR held back in `cr` is the last byte read: on its
    /// own line, whatever follows it.)
    fn line_of(&self, offset: u64) -> u64 {
        self.before + self.ends.partition_point(|&end| end < offset) as u64 + 1
    }
}

/// The offsets in `bytes` of its line ends, as an editor counts them whatever the file's
/// convention (the csv crate reads the three alike): an LF (`\n`, and `\r\n`'s LF: one line
/// end, not two) and a CR not followed by an LF (`\r` alone, an old Mac file's). A CR at the
/// very end, whose next byte is not known, is not listed: `ends_with_cr` says there is one.
fn line_ends(bytes: &[u8]) -> impl Iterator<Item = usize> + '_ {
    let lone_cr = |k: usize| bytes[k] == b'\r' && bytes.get(k + 1).is_some_and(|&b| b != b'\n');
    (0..bytes.len()).filter(move |&k| bytes[k] == b'\n' || lone_cr(k))
}

/// Whether `bytes` ends with a CR ([`line_ends`] leaves it out).
fn ends_with_cr(bytes: &[u8]) -> bool {
    bytes.last() == Some(&b'\r')
}

impl<R: io::Read> io::Read for Lines<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        let (at, bytes) = (self.read, &buf[..n]);
        // The CR that ended the last read is a line end unless this read starts its CRLF (or
        // there is nothing more: the end of the input).
        if let Some(cr) = self.cr.take()
            && bytes.first() != Some(&b'\n')
        {
            self.ends.push_back(cr);
        }
        self.ends.extend(line_ends(bytes).map(|k| at + k as u64));
        if ends_with_cr(bytes) {
            self.cr = Some(at + n as u64 - 1);
        }
        self.read += n as u64;
        Ok(n)
    }
}

/// What is wrong with a row read: its length, or its field `k` (not UTF-8, or not a number).
enum BadRow {
    Length,
    Field(usize),
}

/// The numbers of `record`, a row under a header of `columns` columns.
fn parse_row(record: &csv::ByteRecord, columns: usize) -> Result<Vec<f64>, BadRow> {
    if record.len() != columns {
        return Err(BadRow::Length);
    }
    let number = |bytes: &[u8]| std::str::from_utf8(bytes).ok()?.trim().parse::<f64>().ok();
    record.iter().enumerate().map(|(k, field)| number(field).ok_or(BadRow::Field(k))).collect()
}

/// The error of `record`, a row that is `bad`, named by the line in the file its bad field (or,
/// for a length, the row) starts on: counted back from the record's last line `last` by the
/// newlines of the quoted fields from there on. (From the end, not the start: the position the
/// csv crate gives a record is the end of the one before, blank lines between included.)
#[cold]
fn bad_row(record: &csv::ByteRecord, bad: BadRow, last: u64, columns: &[String]) -> io::Error {
    // A field's own line ends: a CR at its end too (the byte after it, a quote, is no LF).
    let in_field = |f: &[u8]| (line_ends(f).count() + usize::from(ends_with_cr(f))) as u64;
    let newlines = |k: usize| record.iter().skip(k).map(in_field).sum();
    let line_from = |k: usize| usize::try_from(last.saturating_sub(newlines(k))).unwrap_or(usize::MAX);
    let k = match bad {
        BadRow::Field(k) => k,
        BadRow::Length => {
            let (line, len, n) = (line_from(0), record.len(), columns.len());
            let values = if len == 1 { "value" } else { "values" };
            let message = format!("CSV line {line}: a row of {len} {values} under a header of {n} columns");
            return io::Error::new(io::ErrorKind::InvalidData, message);
        }
    };
    let column = columns.get(k).map_or("?", String::as_str);
    match std::str::from_utf8(record.get(k).unwrap_or_default()) {
        Ok(field) => not_a_number(line_from(k), field, column),
        Err(_) => io::Error::new(
            io::ErrorKind::InvalidData,
            format!("CSV line {}: column `{column}` holds text that is not UTF-8", line_from(k)),
        ),
    }
}

/// The CSV of a table of no columns: nothing, for no rows (which reads back as that table),
/// and for `rows` rows an `InvalidInput` error. CSV has no line for a row of no values: the
/// csv crate writes a record of none as `""`, one empty field, which would read back as a
/// column named `""` and its rows as fields that are not numbers.
fn no_columns(rows: usize) -> io::Result<()> {
    if rows == 0 {
        return Ok(());
    }
    let message = format!(
        "a table of {} and no columns cannot be written as CSV, which has no line for a row of no values",
        Count(rows, "row")
    );
    Err(io::Error::new(io::ErrorKind::InvalidInput, message))
}

/// The first column name that appears twice in `columns`, with the positions (from 1) of its
/// first and second appearances: [`Table::column`] would find the first of them alone, the
/// other's values unreachable by name. One pass, with the names seen so far in a map: a
/// mechanism's table can have thousands of columns (its analogs).
fn repeated(columns: &[String]) -> Option<(&str, usize, usize)> {
    let mut seen = std::collections::HashMap::with_capacity(columns.len());
    columns
        .iter()
        .enumerate()
        .find_map(|(k, name)| seen.insert(name.as_str(), k).map(|j| (name.as_str(), j + 1, k + 1)))
}

/// An `InvalidData` error naming the first column name of a CSV header that appears twice.
fn check_distinct(columns: &[String]) -> io::Result<()> {
    match repeated(columns) {
        Some((name, j, k)) => Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("CSV header: the column name `{name}` appears twice (columns {j} and {k})"),
        )),
        None => Ok(()),
    }
}

/// An `InvalidInput` error naming the first column name of a table to be written that appears
/// twice: [`Table::read_csv`] refuses such a header, so the file would not read back.
fn check_distinct_to_write(columns: &[String]) -> io::Result<()> {
    match repeated(columns) {
        Some((name, j, k)) => Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "the column name `{name}` appears twice (columns {j} and {k}): a CSV column is found by its name, \
                 and reading the file back would refuse it"
            ),
        )),
        None => Ok(()),
    }
}

/// An `InvalidInput` error for a table to be written with more units than columns: the header
/// holds one unit per column, and the others were dropped without a word (a unit for each
/// column misaligned, or a column forgotten).
fn check_units_to_write(units: usize, columns: usize) -> io::Result<()> {
    if units <= columns {
        return Ok(());
    }
    Err(io::Error::new(
        io::ErrorKind::InvalidInput,
        format!(
            "the table has {} for {}: the CSV header holds one unit per column, and the others would be lost",
            Count(units, "unit"),
            Count(columns, "column")
        ),
    ))
}

impl Table {
    /// An empty table with these columns.
    pub fn new(columns: Vec<String>) -> Self {
        let units = vec![String::new(); columns.len()];
        Table { columns, rows: Vec::new(), units }
    }

    /// Appends a row (it must have one value per column).
    ///
    /// # Panics
    ///
    /// If the row's length is not the number of columns: a ragged row would read as missing
    /// values (NaN) in [`Table::column`] and fail only later, in [`Table::write_csv`].
    pub fn push(&mut self, row: Vec<f64>) {
        assert!(
            row.len() == self.columns.len(),
            "Table::push: a row of {} for {}",
            Count(row.len(), "value"),
            Count(self.columns.len(), "column")
        );
        self.rows.push(row);
    }

    /// Index of a column: by a mechanism's typed column (`Name::COL.beta`) or by name.
    pub fn index(&self, name: impl ColumnKey) -> Option<usize> {
        let name = name.column_name();
        self.columns.iter().position(|c| c == name)
    }

    /// A column's values: by a mechanism's typed column (`Name::COL.beta`) or by name.
    pub fn column(&self, name: impl ColumnKey) -> Option<Vec<f64>> {
        let k = self.index(name)?;
        Some(self.rows.iter().map(|r| r.get(k).copied().unwrap_or(f64::NAN)).collect())
    }

    /// A column's values with angles in degrees instead of radians, by the column's unit: an
    /// angle (`rad`) times `180/pi`; an analog by the units of its quantity and inputs
    /// (`d(x_c)/d(phi)` from `mm/rad` to `mm/deg`, divided by `180/pi`; `d(beta)/d(phi)`,
    /// `rad/rad`, unchanged; `d2(x_c)/d(phi)^2` divided by its square); a column without angles
    /// (a length) unchanged. Where the table does not know a unit the column needs (a table made
    /// by [`Table::new`] without [`Table::with_units`], a quantity of a kind not inferred) the
    /// column is taken to be an angle, as you ask.
    ///
    /// ```
    /// use kinloop_runtime::Table;
    /// let mut t = Table::new(vec!["phi".into(), "x_c".into(), "d(x_c)/d(phi)".into()]);
    /// t.push(vec![std::f64::consts::PI, 2.0, 180.0]);
    /// let t = t.with_units(&[("phi", "rad"), ("x_c", "mm")]);
    /// assert_eq!(t.column_deg("phi"), Some(vec![180.0]));
    /// assert_eq!(t.column_deg("x_c"), Some(vec![2.0]));
    /// // 180 mm per radian is pi mm per degree.
    /// assert_eq!(t.column_deg("d(x_c)/d(phi)"), Some(vec![std::f64::consts::PI]));
    /// ```
    pub fn column_deg(&self, name: impl ColumnKey) -> Option<Vec<f64>> {
        let name = name.column_name();
        let values = self.column(name)?;
        // Unknown: the caller's word that the column is an angle.
        let power = self.radian_power(name).unwrap_or(1);
        Some(values.into_iter().map(|v| table_units::in_degrees(v, power)).collect())
    }

    /// The power of the radian in the unit of column `name` (see
    /// [`table_units::radian_power`]), from the units of the table's quantities; `None` where
    /// one it needs is not known.
    fn radian_power(&self, name: &str) -> Option<i32> {
        let base: Vec<(&str, &str)> = self
            .columns
            .iter()
            .zip(&self.units)
            .filter(|(c, _)| !table_units::is_analog(c))
            .map(|(c, u)| (c.as_str(), u.as_str()))
            .collect();
        table_units::radian_power(name, &base)
    }

    /// The unit of a column (`""` when none is known).
    pub fn unit(&self, name: impl ColumnKey) -> Option<&str> {
        let k = self.index(name)?;
        Some(self.units.get(k).map_or("", String::as_str))
    }

    /// The table with units for its columns, from the units of the base quantities
    /// (`("phi", "rad")`, `("x_c", "mm")`, a point `("p", "mm")` for `p.x` and `p.y`): the analog
    /// columns get the quotients (`d(x_c)/d(phi)` in `mm/rad`, `d2(x_c)/d(phi)^2` in
    /// `mm/rad^2`). Quantities not given keep the unit their column had (inferred by
    /// [`Table::from_states`], or none).
    pub fn with_units(mut self, base: &[(&str, &str)]) -> Self {
        let had: Vec<(String, String)> = self
            .columns
            .iter()
            .zip(&self.units)
            .filter(|(c, u)| !u.is_empty() && !table_units::is_analog(c))
            .map(|(c, u)| (c.clone(), u.clone()))
            .collect();
        // The units given come first: they win over those the columns had.
        let mut all: Vec<(&str, &str)> = base.to_vec();
        all.extend(had.iter().map(|(c, u)| (c.as_str(), u.as_str())));
        self.units = self.columns.iter().map(|c| table_units::derive(c, &all)).collect();
        self
    }

    /// The table with the unit of length `unit` (`"mm"`) in place of the placeholder
    /// [`LENGTH_UNIT`](crate::LENGTH_UNIT) that [`Table::from_states`] writes for lengths (kinloop
    /// does not know the unit of the parameters).
    ///
    /// ```
    /// use kinloop_runtime::Table;
    /// let mut t = Table::new(vec!["phi".into(), "x_c".into(), "d(x_c)/d(phi)".into()]);
    /// t.push(vec![0.5, 1.0, -0.25]);
    /// let t = t.with_units(&[("phi", "rad"), ("x_c", kinloop_runtime::LENGTH_UNIT)]);
    /// assert_eq!(t.unit("d(x_c)/d(phi)"), Some("length unit/rad"));
    /// let t = t.with_length_unit("mm");
    /// assert_eq!(t.unit("x_c"), Some("mm"));
    /// assert_eq!(t.unit("d(x_c)/d(phi)"), Some("mm/rad"));
    /// ```
    pub fn with_length_unit(self, unit: &str) -> Self {
        let lengths: Vec<String> = self
            .columns
            .iter()
            .zip(&self.units)
            .filter(|(c, u)| u.as_str() == crate::LENGTH_UNIT && !table_units::is_analog(c))
            .map(|(c, _)| c.clone())
            .collect();
        let base: Vec<(&str, &str)> = lengths.iter().map(|c| (c.as_str(), unit)).collect();
        self.with_units(&base)
    }

    /// Writes the table as CSV (header line with the units, then one line per row; shortest
    /// round-trip formatting of every value, so reading it back gives the same bits, positional
    /// for ordinary magnitudes and in exponent notation (`1e300`, `2.08e-17`) for `|v| >= 1e16`
    /// or `0 < |v| < 1e-5`; names and units read back exactly, and what the header cannot
    /// hold, a unit containing ` [` or a name beginning with white space, is an `InvalidInput`
    /// error, as is a table of rows but no columns, whose rows CSV cannot hold; a table of no
    /// columns and no rows is written as nothing). A column name that appears twice is an
    /// `InvalidInput` error naming it, before anything is written: [`Table::read_csv`] refuses
    /// such a header, and what is written reads back. More units than columns is an
    /// `InvalidInput` error naming both counts, as serde refuses such a table: the header has
    /// no place for the others. Fewer is well formed (a missing unit is none), and reads back
    /// with `""` for each missing unit: an equal table, as `==` takes a missing unit for `""`.
    pub fn write_csv(&self, w: impl Write) -> io::Result<()> {
        check_units_to_write(self.units.len(), self.columns.len())?;
        if self.columns.is_empty() {
            return no_columns(self.rows.len());
        }
        check_distinct_to_write(&self.columns)?;
        let mut out = csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(w);
        let header = self
            .columns
            .iter()
            .enumerate()
            .map(|(k, c)| table_units::header(c, self.units.get(k).map_or("", String::as_str)));
        out.write_record(header.collect::<io::Result<Vec<_>>>()?)?;
        // One field buffer for the whole table: no allocation per number.
        let mut field = String::new();
        for row in &self.rows {
            for &v in row {
                field.clear();
                Number(v).push_to(&mut field);
                out.write_field(&field)?;
            }
            out.write_record(None::<&[u8]>)?;
        }
        out.flush()
    }

    /// Reads a table written by [`Table::write_csv`] (or any CSV with a header line and numeric
    /// fields, positional or in exponent notation; `NaN`, `inf` and `-inf` as Rust writes
    /// them). Header fields are trimmed as numbers are (`phi, x` has a column `x`). Errors are
    /// `InvalidData`: a field that is not a number (naming its line and column, and what it
    /// holds or that it is empty), a row of another length than the header (naming its line),
    /// each line numbered as in the file (blank lines and the lines of quoted fields counted;
    /// lines ended by LF, CRLF or CR alone, as the reader reads them),
    /// a column name that appears twice (naming it), or text that is not UTF-8.
    ///
    /// A table holds numbers alone: a file with a column of text is refused at its first row,
    /// naming the column. The command line writes three such files, whose other columns are
    /// numbers: the events of `kinloop sweep --events`
    /// and `kinloop trace --events` (`kind`: `limit position`, `singular crossing`, `kink`),
    /// the candidates of `kinloop synth --csv` (`defects`, empty for a valid candidate) and the
    /// extremes of `kinloop extremes` (`column` and `unit`). Read them with a CSV reader (the
    /// `csv` crate, a spreadsheet).
    pub fn read_csv(r: impl io::Read) -> io::Result<Table> {
        Self::read_csv_from(&mut Self::csv_reader(r))
    }

    /// The reader of [`Table::read_csv`]: flexible, so that a ragged row is refused by its
    /// line in the file.
    fn csv_reader<R: io::Read>(r: R) -> csv::Reader<Lines<R>> {
        csv::ReaderBuilder::new().has_headers(true).flexible(true).from_reader(Lines::new(r))
    }

    /// [`Table::read_csv`] from its reader.
    fn read_csv_from<R: io::Read>(input: &mut csv::Reader<Lines<R>>) -> io::Result<Table> {
        let header = input.headers().map_err(csv_error)?;
        let (columns, units): (Vec<String>, Vec<String>) = header.iter().map(table_units::read_header).unzip();
        check_distinct(&columns)?;
        let mut t = Table { columns, rows: Vec::new(), units };
        let mut record = csv::ByteRecord::new();
        while input.read_byte_record(&mut record).map_err(csv_error)? {
            match parse_row(&record, t.columns.len()) {
                Ok(values) => {
                    t.rows.push(values);
                    // The next record starts here: the lines before it are only counted.
                    let end = input.position().byte();
                    input.get_mut().settle(end);
                }
                Err(bad) => {
                    // The reader stands just past the record's end: its last byte is on its last line.
                    let last = input.get_ref().line_of(input.position().byte().saturating_sub(1));
                    return Err(bad_row(&record, bad, last, &t.columns));
                }
            }
        }
        Ok(t)
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

    /// One row in the order of [`Table::kin_columns`].
    pub fn kin_row<const N: usize, const NI: usize, const NO: usize>(k: &Kin<N, NI, NO>) -> Vec<f64> {
        let second = |d2: &[[[f64; NI]; NI]]| d2.as_flattened().as_flattened().to_vec();
        Self::state_row(
            NI,
            &k.x,
            [
                (&k.q[..], k.dq.as_flattened(), &second(&k.d2q)[..]),
                (&k.out[..], k.dout.as_flattened(), &second(&k.d2out)[..]),
            ],
        )
    }

    /// One row in the order of [`Table::kin_columns`] from flat storage of `ni` inputs: the
    /// inputs, then for the unknowns and for the outputs their values, first analogs (row-major)
    /// and the upper triangle (diagonal included) of each one's second analogs (`ni` by `ni`,
    /// row-major). The one layout of a state's row, for compiled and run-time states alike.
    pub(crate) fn state_row(ni: usize, x: &[f64], groups: [(&[f64], &[f64], &[f64]); 2]) -> Vec<f64> {
        let mut r = x.to_vec();
        for (values, d1, d2) in groups {
            r.extend(values);
            r.extend(d1);
            // Row `a` of a quantity's `ni` by `ni` block, from its diagonal on.
            for (k, row) in d2.chunks_exact(ni.max(1)).enumerate() {
                r.extend(&row[k % ni.max(1)..]);
            }
        }
        r
    }
}

#[cfg(test)]
mod tests {
    use super::Table;

    /// What the reader holds to number the lines stays within what the csv crate reads ahead
    /// (its buffer, 8 KiB, a few thousand lines at most), however long the file: it held eight
    /// bytes for every line of the file (a million lines, 8 MB) until the table was read. The
    /// line numbers of errors are checked in `tests/csv_round_trip.rs`.
    #[test]
    fn the_line_ends_held_stay_within_the_read_ahead() {
        let lines = 200_000;
        let mut text = String::from("a,b\n");
        for k in 0..lines {
            text.push_str(if k % 3 == 0 {
                "1,2\r\n"
            } else if k % 3 == 1 {
                "\n3,4\r"
            } else {
                "5,6\n"
            });
        }
        let mut input = Table::csv_reader(text.as_bytes());
        let table = Table::read_csv_from(&mut input).unwrap();
        assert_eq!(table.rows.len(), lines, "one row each, the blank lines skipped");
        // 8 KiB of read-ahead holds at most 8192 line ends, and a record's own lines.
        let held = input.get_ref().ends.capacity();
        assert!(held <= 2 * 8192, "{held} line ends held for {lines} lines");
    }
}
