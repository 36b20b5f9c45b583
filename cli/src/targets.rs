//! The targets file of `kinloop synth`: rows of numbers separated by commas, blank lines and
//! `#` comments skipped, and a header line allowed first.

use crate::{Failed, exit};
use kinloop_model::Count;
use std::path::Path;

/// The largest targets file read (bytes): some hundred thousand rows, far more targets than a
/// synthesis fits.
pub const MAX_TARGETS_BYTES: usize = 16 << 20;

/// The separators of numbers other than the comma that a row might be written with (a
/// spreadsheet's `;` where the comma is the decimal separator, a tab, spaces, `|`): a line of
/// numbers separated by one of them is a mistake said as such, not a header to skip.
const OTHER_SEPARATORS: [char; 4] = [';', '\t', ' ', '|'];

/// The targets of a file: its rows of numbers, and its header where it has one.
pub struct Targets {
    /// The numeric rows, every row the same width.
    pub rows: Vec<Vec<f64>>,
    /// Each row's line in the file (from 1): where a defect of its target is said to be.
    pub lines: Vec<usize>,
    /// The header line skipped (its number from 1, and its text), if the file has one.
    pub header: Option<(usize, String)>,
}

/// The numeric rows of the targets file `path`, every row the same width, with its header; a
/// usage error naming the file, the line (and the column of a separator that is not the comma)
/// otherwise.
pub fn read(path: &Path) -> Result<Targets, Failed> {
    // A file named by mistake (a device that never ends, a large log) is refused after the most
    // a targets file may have, not read whole into memory.
    let text = crate::read_at_most(path, MAX_TARGETS_BYTES, || {
        exit::usage(format!(
            "{} has more than {MAX_TARGETS_BYTES} bytes, more than a targets file may have (a row per target)",
            path.display()
        ))
    })?;
    let (rows, lines, header) = table(&text).map_err(|why| exit::usage(format!("{} {why}", path.display())))?;
    Ok(Targets { rows, lines, header: header.map(|(n, line)| (n, line.to_string())) })
}

/// The rows of `text` ([`table`]).
#[cfg(test)]
fn rows(text: &str) -> Result<Vec<Vec<f64>>, String> {
    table(text).map(|(rows, ..)| rows)
}

/// The first column of the header `line` whose angle unit (`deg` or `rad`, as `kinloop sweep`
/// writes it, `phi [deg]`) is not the one angles are read in (degrees where `deg` is set):
/// `(column, field, unit)`, the column from 1; `None` where there is none. A table written with
/// `--deg` read without it (or the other way round) was taken in the other unit without a word:
/// degrees read as radians, a fit to other targets.
pub fn angle_unit(line: &str, deg: bool) -> Option<(usize, &str, &'static str)> {
    line.split(',').enumerate().find_map(|(k, field)| {
        let field = unquoted(field);
        let unit = field.strip_suffix(']')?.rsplit_once('[')?.1.trim();
        match (unit, deg) {
            ("deg", false) => Some((k + 1, field, "deg")),
            ("rad", true) => Some((k + 1, field, "rad")),
            _ => None,
        }
    })
}

/// A field of a row without the spaces around it and, where it is quoted (`"1.5"`: a spreadsheet
/// that quotes every field), without its quotes: a quoted number was "not a row of finite
/// numbers", and a first row of them a header, skipped. Numbers hold no comma or quote, so a
/// field needs no more of the RFC 4180 rules to be read.
fn unquoted(field: &str) -> &str {
    let field = field.trim();
    field.strip_prefix('"').and_then(|f| f.strip_suffix('"')).map_or(field, str::trim)
}

/// The rows of a text, each row's line (from 1), and its header line (its number from 1, and its
/// text) where it has one.
type Table<'a> = (Vec<Vec<f64>>, Vec<usize>, Option<(usize, &'a str)>);

/// The rows of `text`, each row's line, and its header line (its number from 1, and its text)
/// where it has one;
/// the error is what is wrong and where (`line 3: ...`), to follow the file's name.
fn table(text: &str) -> Result<Table<'_>, String> {
    // A byte order mark first (a spreadsheet's "CSV UTF-8" writes one) is no part of the first
    // number: left on, it made a row of numbers "not a row of finite numbers", shown unchanged
    // (the mark is invisible).
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut numbers = Vec::new();
    let mut header = None;
    let lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    for (k, (n, line)) in lines.enumerate() {
        if let Some(why) = line.split(',').find_map(underflow) {
            return Err(format!("line {}: {why}", n + 1));
        }
        let row: Result<Vec<f64>, _> = line.split(',').map(|v| unquoted(v).parse::<f64>()).collect();
        match row {
            Ok(row) if row.iter().all(|v| v.is_finite()) => {
                if let Some(first) = rows.first().filter(|f| f.len() != row.len()) {
                    return Err(format!(
                        "line {}: {}, the rows before have {}",
                        n + 1,
                        Count(row.len(), "value"),
                        first.len()
                    ));
                }
                rows.push(row);
                numbers.push(n + 1);
            }
            _ if k == 0 && is_header(line) => header = Some((n + 1, line)),
            _ => {
                return Err(match wrong_separator(line) {
                    Some((column, c)) => format!(
                        "line {}, column {column}: {} between numbers, where the numbers of a row are separated by \
                         commas `,` (and `.` is the decimal point)",
                        n + 1,
                        separator_name(c)
                    ),
                    None => format!("line {}: `{line}` is not a row of finite numbers", n + 1),
                });
            }
        }
    }
    if rows.is_empty() {
        return Err("holds no targets".to_string());
    }
    Ok((rows, numbers, header))
}

/// Why the field `field` is refused where it reads as a number too small for a double
/// (`1e-400`, which `f64` reads as 0), as the command line refuses it
/// ([`crate::numbers::number`]): a target at 0 that was not written so. `None` for any other
/// field.
fn underflow(field: &str) -> Option<String> {
    let field = unquoted(field);
    let zero = field.parse::<f64>().is_ok_and(|v| v == 0.0);
    if zero { crate::numbers::number(field).err() } else { None }
}

/// Whether the first line `line` is a header: none of its fields is a number (one with a typo
/// in a number, or a trailing comma, is a bad row), and it is not numbers separated by another
/// separator than the comma (`1;2` is a row written wrong, not the names of columns).
fn is_header(line: &str) -> bool {
    line.split(',').all(|v| unquoted(v).parse::<f64>().is_err()) && wrong_separator(line).is_none()
}

/// Where `line` is numbers separated, somewhere, by another separator than the comma: the
/// column (from 1, in characters) of the first such separator and the separator. `None` where
/// a field is not made of numbers at all, or every field is one number.
fn wrong_separator(line: &str) -> Option<(usize, char)> {
    let mut first = None;
    let mut start = 0;
    for field in line.split(',') {
        let trimmed = field.trim();
        if trimmed.parse::<f64>().is_err() {
            let mut tokens = trimmed.split(OTHER_SEPARATORS).filter(|t| !t.is_empty());
            // Two numbers at least, and nothing else: numbers with another separator.
            let numbers = tokens.clone().count() >= 2 && tokens.all(|t| t.parse::<f64>().is_ok());
            if !numbers {
                return None;
            }
            if first.is_none() {
                let lead = field.len() - field.trim_start().len();
                let (at, c) = trimmed.char_indices().find(|(_, c)| OTHER_SEPARATORS.contains(c))?;
                first = Some((line[..start + lead + at].chars().count() + 1, c));
            }
        }
        start += field.len() + 1;
    }
    first
}

/// A separator as a message names it: a space and a tab in words, the others quoted.
fn separator_name(c: char) -> String {
    match c {
        ' ' => "a space".to_string(),
        '\t' => "a tab".to_string(),
        c => format!("`{c}`"),
    }
}

#[cfg(test)]
mod tests {
    use super::{rows, table};

    /// Each row's line counts the header, comments and blank lines before it, from 1.
    #[test]
    fn each_row_has_its_line() {
        let (rows, lines, header) = table("# targets\nphi,x\n\n0.5,1\n# moved\n1.5,2\n").unwrap();
        assert_eq!((rows.len(), lines, header), (2, vec![4, 6], Some((2, "phi,x"))));
    }

    #[test]
    fn a_header_is_a_first_line_of_words() {
        assert_eq!(rows("phi,x,y\n10,1,2\n"), Ok(vec![vec![10.0, 1.0, 2.0]]));
        // Names with another separator, and units with spaces: still words.
        assert_eq!(rows("x [mm];y [mm]\n1, 2\n"), Ok(vec![vec![1.0, 2.0]]));
        assert_eq!(rows("# targets\nx\ty\n1,2\n"), Ok(vec![vec![1.0, 2.0]]));
    }

    /// A first line of numbers with a separator other than the comma was taken for a header
    /// and dropped: it is an error naming the line, the column of the separator and the comma.
    #[test]
    fn numbers_with_another_separator_are_an_error_where_it_is() {
        for (text, line, column, what) in [
            ("1;2\n3,4\n", 1, 2, "`;`"),
            ("1;2\n3;4\n", 1, 2, "`;`"),
            ("0,97;1,49\n", 1, 5, "`;`"),
            ("# comment\n  0.97 1.49\n", 2, 7, "a space"),
            ("phi\tx\ty\n10\t1.0\t2.0\n", 2, 3, "a tab"),
            ("1,2\n3,4|5\n", 2, 4, "`|`"),
        ] {
            let e = rows(text).expect_err(text);
            let want = format!("line {line}, column {column}: {what} between numbers");
            assert!(e.starts_with(&want), "{text:?}: {e}");
            assert!(e.contains("separated by commas `,`"), "{text:?}: {e}");
        }
    }

    /// A byte order mark before the first row (a spreadsheet's "CSV UTF-8") is skipped, as it is
    /// before a header; one later in the file is not a number.
    #[test]
    fn a_byte_order_mark_first_is_skipped() {
        assert_eq!(rows("\u{feff}1,2\r\n3,4\r\n"), Ok(vec![vec![1.0, 2.0], vec![3.0, 4.0]]));
        assert_eq!(rows("\u{feff}x,y\n1,2\n"), Ok(vec![vec![1.0, 2.0]]));
        assert!(rows("1,2\n\u{feff}3,4\n").is_err());
    }

    /// A number too small for a double (it reads as 0) is refused where it is, as on the
    /// command line; zeros written as zeros are targets.
    #[test]
    fn a_number_too_small_for_a_double_is_an_error_where_it_is() {
        for (text, line) in [("1e-400,2\n3,4\n", 1), ("1,2\n3, -2.5e-330\n", 2)] {
            let e = rows(text).expect_err(text);
            assert!(e.starts_with(&format!("line {line}: `")), "{text:?}: {e}");
            assert!(e.contains("too small for a 64-bit float"), "{text:?}: {e}");
        }
        assert_eq!(rows("0,-0.0\n0e-400,5e-324\n"), Ok(vec![vec![0.0, -0.0], vec![0.0, 5e-324]]));
    }

    /// Quoted fields (a spreadsheet that quotes every field) are read without their quotes: a
    /// first row of quoted numbers was taken for a header and skipped, the next refused.
    #[test]
    fn quoted_fields_are_read_without_their_quotes() {
        assert_eq!(rows("\"1\",\"2\"\n\"3\", \" 4.5 \"\n"), Ok(vec![vec![1.0, 2.0], vec![3.0, 4.5]]));
        assert_eq!(rows("\"x [mm]\",\"y [mm]\"\n\"1\",2\n"), Ok(vec![vec![1.0, 2.0]]));
        assert!(rows("\"1e-400\",2\n").expect_err("underflow").contains("too small for a 64-bit float"));
        assert_eq!(super::angle_unit("\"phi [deg]\",\"y\"", false), Some((1, "phi [deg]", "deg")));
        // A lone quote is no quoted field.
        assert!(rows("1,2\n\"3,4\n").is_err());
    }

    #[test]
    fn a_row_of_another_width_counts_one_value_in_the_singular() {
        assert_eq!(rows("1,2\n3\n"), Err("line 2: 1 value, the rows before have 2".to_string()));
        assert_eq!(rows("1\n3,4\n"), Err("line 2: 2 values, the rows before have 1".to_string()));
    }
}
