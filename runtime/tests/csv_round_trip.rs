//! The CSV of a table: its header against the expected names and units, its values read back
//! with the csv crate's reader and with `Table::read_csv`, bit for bit.

use kinloop_runtime::Table;

fn sample() -> Table {
    let columns = ["phi", "x_c", "d(x_c)/d(phi)", "d2(x_c)/d(phi)^2", "note, quoted", "p.y"];
    let mut t = Table::new(columns.iter().map(|c| c.to_string()).collect());
    t.push(vec![0.0, 1.0 / 3.0, -2.0 / 7.0, 0.1 + 0.2, f64::NAN, 5e-324]);
    t.push(vec![std::f64::consts::PI, -1e300, f64::INFINITY, -0.0, 1.0, f64::MAX]);
    t.with_units(&[("phi", "rad"), ("x_c", "mm"), ("p", "mm")])
}

#[test]
fn header_carries_units_and_the_csv_crate_reads_it() {
    let t = sample();
    let mut bytes = Vec::new();
    t.write_csv(&mut bytes).unwrap();
    let mut reader = csv::Reader::from_reader(&bytes[..]);
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(
        header,
        ["phi [rad]", "x_c [mm]", "d(x_c)/d(phi) [mm/rad]", "d2(x_c)/d(phi)^2 [mm/rad^2]", "note, quoted", "p.y [mm]"]
    );
    let rows: Vec<Vec<f64>> =
        reader.records().map(|r| r.unwrap().iter().map(|f| f.parse::<f64>().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 2);
    for (read, written) in rows.iter().flatten().zip(t.rows.iter().flatten()) {
        assert!(read.to_bits() == written.to_bits() || (read.is_nan() && written.is_nan()), "{read} vs {written}");
    }
}

#[test]
fn read_csv_restores_the_table() {
    let t = sample();
    let mut bytes = Vec::new();
    t.write_csv(&mut bytes).unwrap();
    let back = Table::read_csv(&bytes[..]).unwrap();
    assert_eq!(back.columns, t.columns);
    assert_eq!(back.units, t.units);
    assert_eq!(back.unit("d(x_c)/d(phi)"), Some("mm/rad"));
    for (read, written) in back.rows.iter().flatten().zip(t.rows.iter().flatten()) {
        assert!(read.to_bits() == written.to_bits() || (read.is_nan() && written.is_nan()));
    }
    // Degrees on request, from radians.
    assert_eq!(back.column_deg("phi").unwrap(), vec![0.0, 180.0]);
}

#[test]
fn a_field_that_is_not_a_number_is_a_typed_error() {
    let err = Table::read_csv("a,b\n1,2\n3,x\n".as_bytes()).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidData);
    assert!(err.to_string().contains("line 3") && err.to_string().contains("column `b`"), "{err}");
}

#[test]
fn far_magnitudes_are_written_in_exponent_notation_and_read_back() {
    let mut t = Table::new(vec!["phi".into(), "x".into()]);
    t.push(vec![1e300, 1e-300]);
    t.push(vec![2.0816681711721685e-17, -1.5e16]);
    // Ordinary magnitudes, and both ends of the positional range, as before.
    t.push(vec![0.00001, 9999999999999998.0]);
    t.push(vec![-0.0, 1234567.875]);
    t.push(vec![5e-324, f64::MAX]);
    let mut bytes = Vec::new();
    t.write_csv(&mut bytes).unwrap();
    assert_eq!(
        String::from_utf8(bytes.clone()).unwrap(),
        "phi,x\n1e300,1e-300\n2.0816681711721685e-17,-1.5e16\n0.00001,9999999999999998\n-0,1234567.875\n\
         5e-324,1.7976931348623157e308\n"
    );
    let back = Table::read_csv(&bytes[..]).unwrap();
    for (read, written) in back.rows.iter().flatten().zip(t.rows.iter().flatten()) {
        assert_eq!(read.to_bits(), written.to_bits(), "{read} vs {written}");
    }
}

#[test]
#[should_panic(expected = "Table::push: a row of 2 values for 6 columns")]
fn a_row_of_the_wrong_length_is_refused_in_every_build() {
    let mut t = sample();
    t.push(vec![1.0, 2.0]);
}

/// Header names are trimmed as the numbers under them are: a hand-written `phi, x [mm]` has
/// the columns `phi` and `x`, in `mm`.
#[test]
fn header_names_are_trimmed_as_numbers_are() {
    let t = Table::read_csv("phi, x [mm] ,\ty\n0, 1.5 ,2\n".as_bytes()).unwrap();
    assert_eq!(t.columns, ["phi", "x", "y"]);
    assert_eq!(t.unit("x"), Some("mm"));
    assert_eq!(t.column("x"), Some(vec![1.5]));
    assert_eq!(t.column("y"), Some(vec![2.0]));
}

/// A name that appears twice (here once it is trimmed) is refused, naming it: `column` would
/// find the first alone.
#[test]
fn a_column_name_that_appears_twice_is_an_error() {
    let err = Table::read_csv("x,y, x\n1,2,3\n".as_bytes()).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidData);
    assert!(err.to_string().contains("`x` appears twice (columns 1 and 3)"), "{err}");
}

/// A name that ends in white space reads back whole; one that begins with it cannot (reading
/// trims it off) and is refused when written.
#[test]
fn names_with_white_space_at_an_end_round_trip_or_are_refused() {
    let mut t = Table::new(vec!["a ".into(), "b".into()]);
    t.push(vec![1.0, 2.0]);
    let mut csv = Vec::new();
    t.write_csv(&mut csv).unwrap();
    assert_eq!(Table::read_csv(&csv[..]).unwrap(), t, "{}", String::from_utf8_lossy(&csv));
    let t = Table::new(vec![" a".into()]);
    assert_eq!(t.write_csv(Vec::new()).unwrap_err().kind(), std::io::ErrorKind::InvalidInput);
}

/// A row of another length than the header is malformed data, as a field that is not a number
/// is: `InvalidData` (it was `Other`), naming the line.
#[test]
fn a_ragged_row_is_invalid_data() {
    let err = Table::read_csv("a,b\n1,2\n3\n".as_bytes()).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidData);
    assert!(err.to_string().contains("CSV line 3: a row of 1 value under a header of 2 columns"), "{err}");
    // Text that is not UTF-8, in the header or a row, likewise.
    for bytes in [&b"a,\xff\n1,2\n"[..], &b"a,b\n1,\xff\n"[..]] {
        assert_eq!(Table::read_csv(bytes).unwrap_err().kind(), std::io::ErrorKind::InvalidData);
    }
}

/// A table of no columns: CSV has no line for a row of no values (the csv crate wrote `""`, the
/// line of one empty field, so that one read back as a column named `""`, and its rows as
/// fields that are not numbers). With no rows it is written as nothing and reads back; with
/// rows it is refused when written.
#[test]
fn a_table_of_no_columns_round_trips_or_is_refused() {
    let empty = Table::new(Vec::new());
    let mut csv = Vec::new();
    empty.write_csv(&mut csv).unwrap();
    assert_eq!(Table::read_csv(&csv[..]).unwrap(), empty, "{}", String::from_utf8_lossy(&csv));
    let mut rows = empty.clone();
    rows.push(Vec::new());
    rows.push(Vec::new());
    let err = rows.write_csv(Vec::new()).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    assert!(err.to_string().contains("2 rows and no columns"), "{err}");
    // One column named `""` is not the same table, and reads back as itself.
    let mut one = Table::new(vec![String::new()]);
    one.push(vec![1.0]);
    let mut csv = Vec::new();
    one.write_csv(&mut csv).unwrap();
    assert_eq!(Table::read_csv(&csv[..]).unwrap(), one);
}

/// What is written reads back: a table naming a column twice (a command's own column and a
/// mechanism's input of the same name, `t` beside the time `t`) is refused when written, as
/// `read_csv` refuses its header, naming the name and both columns. It was written, and the
/// file could not be read back, nor a column of it told from the other by name.
#[test]
fn a_column_name_that_appears_twice_is_refused_when_written() {
    let mut t = Table::new(vec!["t".into(), "omega".into(), "t".into()]);
    t.push(vec![0.0, 150.0, 0.5]);
    let mut csv = Vec::new();
    let err = t.write_csv(&mut csv).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    assert!(err.to_string().contains("the column name `t` appears twice (columns 1 and 3)"), "{err}");
    // Nothing is written: not a header that cannot be read back.
    assert!(csv.is_empty(), "{}", String::from_utf8_lossy(&csv));
    // Names that differ only by their units, or by white space at their end, are distinct and
    // read back as written.
    let mut distinct = Table::new(vec!["x".into(), "x ".into(), "x [mm]".into()]);
    distinct.units = vec!["mm".into(), "mm".into(), String::new()];
    distinct.push(vec![1.0, 2.0, 3.0]);
    let mut csv = Vec::new();
    distinct.write_csv(&mut csv).unwrap();
    assert_eq!(Table::read_csv(&csv[..]).unwrap(), distinct, "{}", String::from_utf8_lossy(&csv));
}

/// Units beyond the columns are refused when written, naming both counts (as serde refuses such
/// a table): the header holds one unit per column, and the others were dropped without a word.
/// Fewer units than columns is well formed, a missing unit none: each reads back as `""`.
#[test]
fn more_units_than_columns_are_refused_when_written() {
    let mut t = Table::new(vec!["phi".into(), "x".into()]);
    t.push(vec![0.5, 1.0]);
    t.units = vec!["rad".into(), "mm".into(), "mm/rad".into()];
    let mut csv = Vec::new();
    let err = t.write_csv(&mut csv).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    assert!(err.to_string().contains("the table has 3 units for 2 columns"), "{err}");
    assert!(csv.is_empty(), "{}", String::from_utf8_lossy(&csv));
    // So is a table of no columns given a unit.
    let none = Table { columns: Vec::new(), rows: Vec::new(), units: vec!["mm".into()] };
    assert_eq!(none.write_csv(Vec::new()).unwrap_err().kind(), std::io::ErrorKind::InvalidInput);
    // Fewer: the missing unit reads back as none.
    t.units = vec!["rad".into()];
    let mut csv = Vec::new();
    t.write_csv(&mut csv).unwrap();
    let back = Table::read_csv(&csv[..]).unwrap();
    assert_eq!((back.units, back.rows), (vec!["rad".to_string(), String::new()], t.rows));
}

/// The edge values of `f64` (NaN, both infinities, both zeros, the smallest subnormal and the
/// largest, the smallest normal, 1e308 and the largest finite) under names a header must quote
/// or keep as they are (a comma, a quote, spaces inside, a line break, non-ASCII letters) with
/// units alike: every name, unit and value reads back, each value to the bit (a NaN as a NaN).
/// The expected bits are the literals' own, written out (printed by `csv_round_trip_bits.py`
/// beside this file, Python's doubles): the table is not its own reference.
#[test]
fn edge_values_and_awkward_names_read_back_to_the_bit() {
    let values = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        0.0,
        -0.0,
        5e-324,
        -2.225073858507201e-308,
        f64::MIN_POSITIVE,
        1e308,
        -f64::MAX,
        0.1 + 0.2,
    ];
    let bits: [u64; 11] = [
        0x7ff8_0000_0000_0000,
        0x7ff0_0000_0000_0000,
        0xfff0_0000_0000_0000,
        0x0000_0000_0000_0000,
        0x8000_0000_0000_0000,
        0x0000_0000_0000_0001,
        0x800f_ffff_ffff_ffff,
        0x0010_0000_0000_0000,
        0x7fe1_ccf3_85eb_c8a0,
        0xffef_ffff_ffff_ffff,
        0x3fd3_3333_3333_3334,
    ];
    let names = ["a,b", "say \"hi\"", "with  spaces", "line\nbreak", "φ₁ of Ünïcode", "x ", "ok"];
    let units = ["µm", "°/s", "a, \"b\"", "", "N·m", "m s", "kg/(m s)^2"];
    let mut t = Table::new(names.iter().map(|n| n.to_string()).collect());
    t.units = units.iter().map(|u| u.to_string()).collect();
    // Each value in each column: the rows are the values turned by one place per column.
    for r in 0..values.len() {
        t.push((0..names.len()).map(|c| values[(r + c) % values.len()]).collect());
    }
    let mut csv = Vec::new();
    t.write_csv(&mut csv).unwrap();
    let text = String::from_utf8(csv.clone()).unwrap();
    let back = Table::read_csv(&csv[..]).unwrap_or_else(|e| panic!("{e}:\n{text}"));
    assert_eq!((&back.columns, &back.units), (&t.columns, &t.units), "{text}");
    assert_eq!(back.rows.len(), values.len());
    for (r, row) in back.rows.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            let want = bits[(r + c) % values.len()];
            // NaN's payload is not written: any NaN reads back as the quiet NaN `f64::NAN` is.
            assert_eq!(v.to_bits(), want, "row {r}, column {c}: {v:e}\n{text}");
        }
    }
}

/// Fewer units than columns is well formed, a missing unit none: the CSV reads back with `""`
/// for it, and that is the same table (`==` takes a missing unit for `""`), where it compared
/// unequal to the table written. A unit that differs still makes the tables differ.
#[test]
fn a_table_of_fewer_units_than_columns_reads_back_as_itself() {
    let mut t = Table::new(vec!["phi".into(), "x".into(), "y".into()]);
    t.push(vec![0.5, 1.0, -2.0]);
    for units in [vec![], vec!["rad".to_string()], vec!["rad".to_string(), String::new()]] {
        let t = Table { units, ..t.clone() };
        let mut csv = Vec::new();
        t.write_csv(&mut csv).unwrap();
        let back = Table::read_csv(&csv[..]).unwrap();
        assert_eq!(back.units.len(), 3, "{:?}", back.units);
        assert_eq!(back, t, "{}", String::from_utf8_lossy(&csv));
        assert_eq!(t, back);
    }
    let with_rad = Table { units: vec!["rad".into()], ..t.clone() };
    let with_mm = Table { units: vec!["rad".into(), String::new(), "mm".into()], ..t.clone() };
    assert_ne!(with_rad, with_mm);
    assert_ne!(with_mm, with_rad);
    assert_ne!(Table { units: vec![], ..t.clone() }, with_rad);
}

/// A column of text (the command line's events, candidates and extremes have one) is refused
/// at its first row naming the column and what it holds, an empty field as empty (quoted, it
/// read as a misprint), and saying that a table holds numbers alone.
#[test]
fn a_column_of_text_is_refused_naming_it_and_saying_why() {
    let events = "kind,tau,phi [rad]\nlimit position,0.25,1.5\n";
    let err = Table::read_csv(events.as_bytes()).unwrap_err().to_string();
    assert!(err.contains("CSV line 2: column `kind` holds `limit position`, which is not a number"), "{err}");
    assert!(err.contains("a table holds numbers alone"), "{err}");
    let candidates = "rank,start,valid,a,max_error,defects\n1,0,1,1.1,0.001,\"\"\n";
    let err = Table::read_csv(candidates.as_bytes()).unwrap_err().to_string();
    assert!(err.contains("CSV line 2: column `defects` is empty, which is not a number"), "{err}");
    let blank = Table::read_csv("a,b\n1, \n".as_bytes()).unwrap_err().to_string();
    assert!(blank.contains("column `b` is empty"), "{blank}");
}

/// A bad field is named by its line in the file, as an editor numbers it: blank lines before
/// it (which the reader skips) and a quoted field that runs over several lines count, as a
/// ragged row's line does. Counted by hand in the texts below. It was the row's number plus
/// one, line 3 for the field on line 6.
#[test]
fn a_bad_field_is_named_by_its_line_in_the_file() {
    let blank_lines = "a,b\n\n1,2\n\n\n3,x\n";
    let err = Table::read_csv(blank_lines.as_bytes()).unwrap_err().to_string();
    assert!(err.contains("CSV line 6: column `b` holds `x`"), "{err}");
    // A record whose quoted field runs over lines 2 to 4: the next record is on line 5.
    let quoted = "a,b\n\"1\n\n\",2\n3,x\n";
    let err = Table::read_csv(quoted.as_bytes()).unwrap_err().to_string();
    assert!(err.contains("CSV line 5: column `b` holds `x`"), "{err}");
    // A field after one that runs from line 2 to 3: on line 3, not on its record's first line.
    let after = "a,b\n\"1\n\",x\n";
    let err = Table::read_csv(after.as_bytes()).unwrap_err().to_string();
    assert!(err.contains("CSV line 3: column `b` holds `x`"), "{err}");
    let ragged = "a,b\n\n\n1,2,3\n";
    let err = Table::read_csv(ragged.as_bytes()).unwrap_err().to_string();
    assert!(err.contains("CSV line 4: a row of 3 values"), "{err}");
    let not_utf8 = Table::read_csv(&b"a,b\n\n1,\xff\n"[..]).unwrap_err().to_string();
    assert!(not_utf8.contains("CSV line 3: column `b` holds text that is not UTF-8"), "{not_utf8}");
}

/// A reader that hands over one byte a call: a CR at the end of one read and its LF at the
/// start of the next, as a buffered file may split them.
struct ByteAtATime<'a>(&'a [u8]);

impl std::io::Read for ByteAtATime<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        match (self.0.split_first(), buf.first_mut()) {
            (Some((&b, rest)), Some(slot)) => {
                *slot = b;
                self.0 = rest;
                Ok(1)
            }
            _ => Ok(0),
        }
    }
}

/// The lines of a file are numbered alike whatever ends them: LF, CRLF (a spreadsheet's, one
/// line end, not two) or CR alone (an old Mac file's, which the csv crate reads as line ends
/// too). The texts of `a_bad_field_is_named_by_its_line_in_the_file` with each LF replaced,
/// the lines counted there by hand; read whole and a byte at a time (a CRLF split between two
/// reads). A CR-only file was named line 1 for every row, a quoted field over lines counted as
/// one line.
#[test]
fn a_bad_field_s_line_is_counted_alike_for_lf_crlf_and_cr_line_ends() {
    let cases = [
        ("a,b\n\n1,2\n\n\n3,x\n", "CSV line 6: column `b` holds `x`"),
        ("a,b\n\"1\n\n\",2\n3,x\n", "CSV line 5: column `b` holds `x`"),
        ("a,b\n\"1\n\",x\n", "CSV line 3: column `b` holds `x`"),
        ("a,b\n\n\n1,2,3\n", "CSV line 4: a row of 3 values"),
        ("a,b\n\n1,x", "CSV line 3: column `b` holds `x`"),
    ];
    for (text, expected) in cases {
        for end in ["\n", "\r\n", "\r"] {
            let bytes = text.replace('\n', end).into_bytes();
            for (how, read) in
                [("whole", Table::read_csv(&bytes[..])), ("bytewise", Table::read_csv(ByteAtATime(&bytes)))]
            {
                let err = read.unwrap_err().to_string();
                assert!(err.contains(expected), "{how} {end:?} {text:?}: {err}");
            }
        }
    }
}

/// A file as a spreadsheet saves it: a UTF-8 byte order mark before the header, lines ended
/// by CRLF, a blank line at the end. The mark is not part of the first name, nor the CR of
/// the last field's value: the same table as the plain file.
#[test]
fn a_spreadsheet_s_file_reads_as_the_plain_one() {
    let plain = Table::read_csv("phi [rad],x [mm]\n0.5,1.25\n-0,1e-300\n".as_bytes()).unwrap();
    let saved = Table::read_csv("\u{feff}phi [rad],x [mm]\r\n0.5,1.25\r\n-0,1e-300\r\n\r\n".as_bytes()).unwrap();
    assert_eq!(saved, plain);
    assert_eq!(saved.columns, ["phi", "x"]);
    assert_eq!(saved.unit("x"), Some("mm"));
    assert_eq!(saved.rows[1][0].to_bits(), (-0.0f64).to_bits());
}
