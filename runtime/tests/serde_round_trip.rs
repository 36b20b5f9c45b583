//! With the feature `serde`, values of the runtime's vocabulary survive a JSON round trip
//! unchanged, bit for bit (serde_json writes the shortest representation that reads back
//! exactly).
#![cfg(feature = "serde")]

use kinloop_runtime::{AtSingular, Event, EventKind, NewtonConfig, SweepConfig, Table, TraceConfig, Vec2};
use serde::Serialize;
use serde::de::DeserializeOwned;

fn round_trip<T: Serialize + DeserializeOwned>(value: &T) -> T {
    let json = serde_json::to_string(value).expect("serializes");
    serde_json::from_str(&json).unwrap_or_else(|e| panic!("{json} does not read back: {e}"))
}

#[test]
fn configurations_round_trip() {
    let newton = NewtonConfig::default().with_residual_tol(1e-14).with_max_iterations(7);
    assert_eq!(round_trip(&newton), newton);
    let sweep = SweepConfig::default().with_newton(newton).with_max_step(0.3).with_at_singular(AtSingular::Continue);
    assert_eq!(round_trip(&sweep), sweep);
    // Field names are the documented ones, so a configuration file reads naturally.
    let json = serde_json::to_value(sweep).unwrap();
    assert_eq!(json["max_step"], 0.3);
    assert_eq!(json["newton"]["max_iterations"], 7);
    assert_eq!(json["at_singular"], "Continue");
    // A configuration written before `restarts` existed reads with its default.
    let mut older = serde_json::to_value(newton.with_restarts(false)).unwrap();
    older.as_object_mut().unwrap().remove("restarts");
    assert_eq!(serde_json::from_value::<NewtonConfig>(older).unwrap(), newton);
    assert!(!round_trip(&newton.with_restarts(false)).restarts);
    for opts in [TraceConfig::default(), TraceConfig::default().with_ds(0.03).with_newton(newton)] {
        assert_eq!(round_trip(&opts), opts);
    }
}

#[test]
fn tables_and_vectors_round_trip_bit_for_bit() {
    let mut t = Table::new(vec!["phi [rad]".into(), "x_c [length]".into()]);
    // Values whose shortest decimal forms are long: a lossy writer would change their bits.
    t.push(vec![std::f64::consts::PI / 3.0, 0.1 + 0.2]);
    t.push(vec![f64::MIN_POSITIVE, -1.0e300 / 3.0]);
    let back = round_trip(&t);
    assert_eq!(back.columns, t.columns);
    for (a, b) in back.rows.iter().flatten().zip(t.rows.iter().flatten()) {
        assert_eq!(a.to_bits(), b.to_bits());
    }
    let v = Vec2::new(0.1, -7.0 / 3.0);
    assert_eq!(round_trip(&v), v);
}

#[test]
fn events_round_trip_without_their_static_block() {
    let e = Event { kind: EventKind::LimitPosition, x: vec![1.25], tau: 0.5, q: vec![0.1, 2.0], block: None };
    assert_eq!(round_trip(&e), e);
    assert_eq!(round_trip(&EventKind::SingularCrossing), EventKind::SingularCrossing);
}

/// A table read from JSON has the shape [`Table::push`] keeps: a row of another length than
/// the columns, or more units than columns, is an error saying so. Read unchecked, the
/// missing value of a short row was NaN in `Table::column`, without an error.
#[test]
fn a_table_of_the_wrong_shape_is_refused_saying_where() {
    let short = r#"{"columns":["phi","x"],"rows":[[0.5,1.0],[0.75]],"units":["rad","mm"]}"#;
    let err = serde_json::from_str::<Table>(short).unwrap_err().to_string();
    assert!(err.contains("row 2 of the table has 1 value for 2 columns"), "{err}");
    let long = r#"{"columns":["phi"],"rows":[[0.5,1.0]]}"#;
    let err = serde_json::from_str::<Table>(long).unwrap_err().to_string();
    assert!(err.contains("row 1 of the table has 2 values for 1 column") && !err.contains("1 columns"), "{err}");
    let units = r#"{"columns":["phi"],"rows":[[0.5]],"units":["rad","mm"]}"#;
    let err = serde_json::from_str::<Table>(units).unwrap_err().to_string();
    assert!(err.contains("the table has 2 units for 1 column") && !err.contains("1 columns"), "{err}");
    // A name twice, as `read_csv` refuses it: `Table::column` would find the first alone.
    let twice = r#"{"columns":["x","y","x"],"rows":[[1.0,2.0,3.0]]}"#;
    let err = serde_json::from_str::<Table>(twice).unwrap_err().to_string();
    assert!(err.contains("the column name `x` appears twice (columns 1 and 3)"), "{err}");
    // Well formed, with fewer units than columns (a missing one is none) or none at all.
    let fewer: Table = serde_json::from_str(r#"{"columns":["phi","x"],"rows":[[0.5,1.0]],"units":["rad"]}"#).unwrap();
    assert_eq!((fewer.unit("phi"), fewer.unit("x"), fewer.column("x")), (Some("rad"), Some(""), Some(vec![1.0])));
    let none: Table = serde_json::from_str(r#"{"columns":["phi"],"rows":[]}"#).unwrap();
    assert_eq!(none, Table { columns: vec!["phi".into()], rows: Vec::new(), units: Vec::new() });
    // Read with one unit per column, as from CSV: a missing one is `""`.
    assert_eq!((fewer.units, none.units), (vec!["rad".to_string(), String::new()], vec![String::new()]));
}

/// The edge values of `f64` and names and units a CSV header would quote, through JSON: every
/// name and unit as written, every value to the bit (the literals' bits written out, NaN as
/// the quiet NaN, printed by `csv_round_trip_bits.py` beside this file); a table of fewer
/// units than columns reads back as the same table.
#[test]
fn a_table_of_edge_values_and_awkward_names_reads_back_from_json() {
    let values = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -0.0, 5e-324, -2.225073858507201e-308, 1e308, 0.1 + 0.2];
    let bits: [u64; 8] = [
        0x7ff8_0000_0000_0000,
        0x7ff0_0000_0000_0000,
        0xfff0_0000_0000_0000,
        0x8000_0000_0000_0000,
        0x0000_0000_0000_0001,
        0x800f_ffff_ffff_ffff,
        0x7fe1_ccf3_85eb_c8a0,
        0x3fd3_3333_3333_3334,
    ];
    let mut t = Table::new(vec!["a,b".into(), "say \"hi\"".into(), "φ₁ Ünï".into()]);
    t.units = vec!["µm".into(), "a, \"b\"".into()];
    for r in 0..values.len() {
        t.push((0..3).map(|c| values[(r + c) % values.len()]).collect());
    }
    let json = serde_json::to_string(&t).unwrap();
    let back: Table = serde_json::from_str(&json).unwrap_or_else(|e| panic!("{json}: {e}"));
    assert_eq!(back.columns, t.columns);
    assert_eq!(back.units, ["µm", "a, \"b\"", ""]);
    for (r, row) in back.rows.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            assert_eq!(v.to_bits(), bits[(r + c) % values.len()], "row {r}, column {c}: {json}");
        }
    }
    let finite = Table { rows: vec![vec![-0.0, 5e-324, 1e308]], ..t.clone() };
    assert_eq!(round_trip(&finite), finite);
}

/// A state of other sizes is refused naming the field, or the row of it, whose length does
/// not fit: `dq[1]` has one entry per input, where `dq` has one row per unknown.
#[test]
fn a_state_of_other_sizes_is_refused_naming_the_row() {
    use kinloop_runtime::{Health, Kin, SolveReport};
    let k = Kin::<2, 1, 1> {
        x: [0.5],
        q: [1.0, 2.0],
        dq: [[0.1], [0.2]],
        d2q: [[[0.3]], [[0.4]]],
        out: [3.0],
        dout: [[0.5]],
        d2out: [[[0.6]]],
        report: SolveReport::direct(),
        health: Health { min_pivot: 0.5, ..Health::default() },
    };
    let json = serde_json::to_string(&k).unwrap();
    assert_eq!(serde_json::from_str::<Kin<2, 1, 1>>(&json).unwrap(), k);
    let error = |json: &str| serde_json::from_str::<Kin<2, 1, 1>>(json).unwrap_err().to_string();
    let wide = json.replace("[[0.1],[0.2]]", "[[0.1],[0.2,0.7]]");
    assert!(error(&wide).contains("`dq[1]` has 2 entries where the mechanism has 1"), "{}", error(&wide));
    let tall = json.replace("[[0.1],[0.2]]", "[[0.1],[0.2],[0.7]]");
    assert!(error(&tall).contains("`dq` has 3 entries where the mechanism has 2"), "{}", error(&tall));
    let deep = json.replace("[[[0.3]],[[0.4]]]", "[[[0.3]],[[0.4,0.8]]]");
    assert!(error(&deep).contains("`d2q[1][0]` has 2 entries where the mechanism has 1"), "{}", error(&deep));
}

/// JSON has no NaN nor infinity: a table holding them (a synthesis report's table has NaN
/// where a value was not asked) writes them as `"NaN"`, `"inf"` and `"-inf"` and reads them
/// back as they were, where serde_json's `null` did not read back ("invalid type: null,
/// expected f64"); `null`, which earlier writers wrote, reads as NaN. Whole numbers written by
/// hand read as well.
#[test]
fn a_table_with_nan_reads_back_from_json() {
    let mut t = Table::new(vec!["valid".into(), "min_transmission".into()]);
    t.push(vec![1.0, f64::NAN]);
    t.push(vec![0.0, f64::INFINITY]);
    t.push(vec![-0.0, f64::NEG_INFINITY]);
    t.push(vec![0.5, 0.1 + 0.2]);
    let json = serde_json::to_string(&t).unwrap();
    assert!(json.contains(r#"[1.0,"NaN"],[0.0,"inf"],[-0.0,"-inf"]"#), "{json}");
    let bits = |t: &Table| {
        t.rows.iter().flatten().map(|v| if v.is_nan() { u64::MAX } else { v.to_bits() }).collect::<Vec<_>>()
    };
    let back: Table = serde_json::from_str(&json).unwrap();
    assert_eq!((&back.columns, bits(&back)), (&t.columns, bits(&t)));
    let nulls = json.replace(r#""NaN""#, "null").replace(r#""-inf""#, "null").replace(r#""inf""#, "null");
    let old: Table = serde_json::from_str(&nulls).unwrap_or_else(|e| panic!("{nulls}: {e}"));
    assert!(old.rows[0][1].is_nan() && old.rows[1][1].is_nan() && old.rows[2][1].is_nan(), "{old:?}");
    let by_hand: Table = serde_json::from_str(r#"{"columns":["n"],"rows":[[3],[-2]]}"#).unwrap();
    assert_eq!(by_hand.column("n"), Some(vec![3.0, -2.0]));
    let err = serde_json::from_str::<Table>(r#"{"columns":["n"],"rows":[["x"]]}"#).unwrap_err().to_string();
    assert!(err.contains(r#"expected a number, "inf", "-inf", "NaN", or null for NaN"#), "{err}");
}

/// A state none of whose blocks was factorised (every unknown solved in closed form, or none)
/// has an infinite `health.min_pivot`, which JSON writes as `"inf"`: it reads back as that
/// infinity, where serde_json's `null` was an error ("invalid type: null, expected f64"). A
/// pivot ratio is never NaN, so `null`, which earlier writers wrote, reads as the infinity too.
#[test]
fn a_state_with_no_pivot_reads_back_from_json() {
    use kinloop_runtime::{Health, Kin, SolveReport};
    let k = Kin::<1, 1, 0> {
        x: [0.5],
        q: [-0.0],
        dq: [[f64::MIN_POSITIVE / 4.0]],
        d2q: [[[1e308]]],
        out: [],
        dout: [],
        d2out: [],
        report: SolveReport::direct(),
        health: Health::default(),
    };
    assert_eq!(k.health.min_pivot, f64::INFINITY);
    let json = serde_json::to_string(&k).unwrap();
    assert!(json.contains(r#""min_pivot":"inf""#), "{json}");
    let back = serde_json::from_str::<Kin<1, 1, 0>>(&json).unwrap_or_else(|e| panic!("{json}: {e}"));
    assert_eq!(back, k);
    // Every value to the bit: the sign of the zero, the subnormal, the largest magnitude.
    assert_eq!(back.q[0].to_bits(), k.q[0].to_bits());
    assert_eq!(back.dq[0][0].to_bits(), k.dq[0][0].to_bits());
    // A finite pivot ratio, and one written by hand as a whole number, read as they are.
    let old = json.replace(r#""min_pivot":"inf""#, r#""min_pivot":null"#);
    assert_eq!(serde_json::from_str::<Kin<1, 1, 0>>(&old).unwrap(), k);
    let finite = json.replace(r#""min_pivot":"inf""#, r#""min_pivot":0.25"#);
    assert_eq!(serde_json::from_str::<Kin<1, 1, 0>>(&finite).unwrap().health.min_pivot, 0.25);
    let whole = json.replace(r#""min_pivot":"inf""#, r#""min_pivot":1"#);
    assert_eq!(serde_json::from_str::<Kin<1, 1, 0>>(&whole).unwrap().health.min_pivot, 1.0);
}

/// A synthesis report holds non-finite values where a candidate is degenerate: the ratio of a
/// zero-length link is infinite (`0/0` NaN where every link is zero), an error that cannot be
/// evaluated is NaN. JSON has no NaN nor infinity and wrote them as `null`, which did not read
/// back ("invalid type: null, expected f64"). Every value comes back as it was: a non-finite
/// one is written as the string Rust prints for it, so that an infinity stays an infinity and
/// a `Some` of one is not taken for `None` (`null`).
#[test]
fn a_synthesis_report_with_non_finite_values_reads_back_exactly() {
    use kinloop_runtime::analysis::OptimizerStop;
    use kinloop_runtime::metrics::GrashofClass;
    use kinloop_runtime::synthesis::{
        Candidate, Defect, FourBarClass, LocalReport, Origin, Rejections, SynthesisReport,
    };
    let (inf, nan) = (f64::INFINITY, f64::NAN);
    let candidate = Candidate {
        start: 2,
        origin: Origin::Halton,
        values: vec![0.0, nan, -0.0],
        params: vec![0.0, nan, -0.0, inf],
        inputs: vec![vec![0.1], vec![-inf]],
        placement: Some([nan, inf, -inf, 1.0]),
        positions: vec![vec![nan, 1.0], vec![0.5, inf]],
        errors: vec![0.25, nan],
        max_error: 0.25,
        rms_error: nan,
        defects: vec![
            Defect::LinkRatio { ratio: inf },
            Defect::LinkRatio { ratio: nan },
            Defect::Miss { target: 1, error: nan },
            Defect::Circuit { target: 1, at: nan },
            Defect::Transmission { min: -inf },
        ],
        min_transmission: Some(inf),
        four_bar: Some(FourBarClass { class: GrashofClass::ChangePoint, margin: nan, min_transmission: inf }),
        local: LocalReport { evaluations: 1, iterations: 0, stop: OptimizerStop::Stalled, residual: inf },
    };
    let none = Candidate { min_transmission: None, four_bar: None, placement: None, ..candidate.clone() };
    let mut report =
        SynthesisReport::new(vec!["a".into(), "b".into(), "c".into()], vec![(0.0, 1.0), (-inf, inf), (0.5, 0.5)]);
    report.candidates = vec![candidate, none];
    report.starts = 0..4;
    report.unassembled = 2;
    report.rejected = Rejections { link_ratio: 2, ..Rejections::default() };
    report.evaluations = 9;
    report.four_bar = true;
    let back = round_trip(&report);
    // The same values to the bit, `Some` and `None` as they were.
    let json = serde_json::to_string(&report).unwrap();
    assert!(
        json.contains(r#"{"LinkRatio":{"ratio":"inf"}}"#) && json.contains(r#""min_transmission":"inf""#),
        "{json}"
    );
    let again = serde_json::to_string(&back).unwrap();
    assert_eq!(again, json);
    assert_eq!(back.candidates[0].min_transmission, Some(inf));
    assert_eq!(back.candidates[1].min_transmission, None);
    assert_eq!(back.candidates[0].defects[0], Defect::LinkRatio { ratio: inf });
    assert!(matches!(back.candidates[0].defects[1], Defect::LinkRatio { ratio } if ratio.is_nan()));
    assert_eq!(back.bounds[1], (-inf, inf));
    assert_eq!(back.candidates[0].values[2].to_bits(), (-0.0f64).to_bits());
    assert!(back.candidates[0].rms_error.is_nan() && back.candidates[0].local.residual == inf);
    // What older writers wrote (and a hand-written file may hold): `null` for a plain number
    // reads as NaN, and as `None` where the field is optional.
    let nulls = json.replace("\"inf\"", "null").replace("\"-inf\"", "null").replace("\"NaN\"", "null");
    let read: SynthesisReport = serde_json::from_str(&nulls).unwrap_or_else(|e| panic!("{nulls}: {e}"));
    assert!(matches!(read.candidates[0].defects[0], Defect::LinkRatio { ratio } if ratio.is_nan()));
    assert_eq!(read.candidates[0].min_transmission, None);
    assert!(read.candidates[0].placement.is_some_and(|p| p[0].is_nan() && p[3] == 1.0));
    // A string that is no number is refused, saying what a number may be written as.
    let word = json.replacen("\"NaN\"", "\"none\"", 1);
    let err = serde_json::from_str::<SynthesisReport>(&word).unwrap_err().to_string();
    assert!(err.contains("expected a number, \"inf\", \"-inf\", \"NaN\", or null for NaN"), "{err}");
}

/// The edge values of `f64` with their IEEE-754 bits, as `csv_round_trip_bits.py` (beside this
/// file) prints them from Python's own doubles: NaN, both infinities, both zeros, the smallest
/// and largest subnormals, the smallest normal, the largest finite magnitude, a long decimal.
const EDGES: [(f64, u64); 11] = [
    (f64::NAN, 0x7ff8_0000_0000_0000),
    (f64::INFINITY, 0x7ff0_0000_0000_0000),
    (f64::NEG_INFINITY, 0xfff0_0000_0000_0000),
    (0.0, 0x0000_0000_0000_0000),
    (-0.0, 0x8000_0000_0000_0000),
    (5e-324, 0x0000_0000_0000_0001),
    (-2.225073858507201e-308, 0x800f_ffff_ffff_ffff),
    (2.2250738585072014e-308, 0x0010_0000_0000_0000),
    (1e308, 0x7fe1_ccf3_85eb_c8a0),
    (-1.7976931348623157e308, 0xffef_ffff_ffff_ffff),
    (0.30000000000000004, 0x3fd3_3333_3333_3334),
];

/// `v` is the edge value of bits `bits`, bit for bit (a NaN too: JSON keeps its sign and payload).
fn is_edge(v: f64, bits: u64) -> bool {
    v.to_bits() == bits
}

/// A state holding every edge value in every field, the `k`-th number (row-major, in field
/// order) the `k`-th edge value cyclically; the solve report's residual infinite.
fn edge_state() -> kinloop_runtime::Kin<3, 2, 2> {
    use kinloop_runtime::{Health, Kin, SolveReport};
    let mut k = 0;
    let mut next = || {
        k += 1;
        EDGES[(k - 1) % EDGES.len()].0
    };
    Kin {
        x: [next(), next()],
        q: [next(), next(), next()],
        dq: [[next(), next()], [next(), next()], [next(), next()]],
        d2q: std::array::from_fn(|_| [[next(), next()], [next(), next()]]),
        out: [next(), next()],
        dout: [[next(), next()], [next(), next()]],
        d2out: std::array::from_fn(|_| [[next(), next()], [next(), next()]]),
        report: SolveReport::given(f64::INFINITY),
        health: Health { min_pivot: 0.25, ..Health::default() },
    }
}

/// Every number of a state in field order, row-major.
fn numbers(k: &kinloop_runtime::Kin<3, 2, 2>) -> Vec<f64> {
    let mut v = Vec::new();
    v.extend(k.x);
    v.extend(k.q);
    v.extend(k.dq.iter().flatten());
    v.extend(k.d2q.iter().flatten().flatten());
    v.extend(k.out);
    v.extend(k.dout.iter().flatten());
    v.extend(k.d2out.iter().flatten().flatten());
    v
}

/// Every number of `back` is the edge value `edge_state` put there, bit for bit.
fn assert_edges(back: &kinloop_runtime::Kin<3, 2, 2>, text: &str) {
    for (n, v) in numbers(back).into_iter().enumerate() {
        let (_, bits) = EDGES[n % EDGES.len()];
        assert!(is_edge(v, bits), "number {n}: {v:e} ({:#x}) for {bits:#x}: {text}", v.to_bits());
    }
}

/// A state holding NaN, the infinities, a negative zero, subnormals and the largest finite value
/// reads back from JSON as it was, bit for bit: JSON, which has no NaN nor infinity, wrote them
/// as `null`, which did not read back ("invalid type: null, expected f64"); they are now the
/// strings Rust prints. `null` written by hand, as earlier versions wrote, reads as NaN.
#[test]
fn a_state_of_edge_values_reads_back_from_json_bit_for_bit() {
    let k = edge_state();
    let json = serde_json::to_string(&k).unwrap();
    assert!(json.contains(r#""x":["NaN","inf"],"q":["-inf",0.0,-0.0]"#), "{json}");
    assert!(json.contains(r#""residual":"inf""#), "{json}");
    let back: kinloop_runtime::Kin<3, 2, 2> =
        serde_json::from_str(&json).unwrap_or_else(|e| panic!("{json} does not read back: {e}"));
    assert_edges(&back, &json);
    assert_eq!(back.report.residual, f64::INFINITY);
    assert_eq!((back.report.iterations, back.health), (k.report.iterations, k.health));
    // Written by hand, or by an earlier version: `null` for a number is NaN.
    let nulls = json.replace(r#""NaN""#, "null").replace(r#""-inf""#, "null").replace(r#""inf""#, "null");
    let old: kinloop_runtime::Kin<3, 2, 2> =
        serde_json::from_str(&nulls).unwrap_or_else(|e| panic!("{nulls} does not read: {e}"));
    assert!(old.x[0].is_nan() && old.x[1].is_nan() && old.q[0].is_nan() && old.report.residual.is_nan(), "{old:?}");
    assert_eq!(old.q[2].to_bits(), (-0.0f64).to_bits());
}

/// A compact binary format (CBOR, not human-readable) holds a state's `f64`s themselves, not
/// the strings JSON gets: the edge values read back bit for bit, and no number is text.
#[test]
fn a_state_of_edge_values_reads_back_from_cbor_as_numbers() {
    let k = edge_state();
    let mut bytes = Vec::new();
    ciborium::into_writer(&k, &mut bytes).unwrap();
    let text = String::from_utf8_lossy(&bytes).into_owned();
    assert!(!text.contains("NaN") && !text.contains("inf"), "{text}");
    let back: kinloop_runtime::Kin<3, 2, 2> = ciborium::from_reader(bytes.as_slice()).unwrap();
    assert_edges(&back, &text);
    assert_eq!(back.report.residual, f64::INFINITY);
}

/// A vector of any component type reads back from JSON with every number as it was: `Vec2<f64>`
/// and the several inputs' analogs `Vec2<[f64; 2]>` (serde_json's `null` for a NaN or an
/// infinity did not read back), and component types without numbers, or with optional ones,
/// as before.
#[test]
fn vectors_of_edge_values_read_back_from_json_bit_for_bit() {
    for pair in EDGES.windows(2) {
        let v = Vec2::new(pair[0].0, pair[1].0);
        let json = serde_json::to_string(&v).unwrap();
        let back: Vec2 = serde_json::from_str(&json).unwrap_or_else(|e| panic!("{json}: {e}"));
        assert!(is_edge(back.x, pair[0].1) && is_edge(back.y, pair[1].1), "{json}: {back:?}");
    }
    let many = Vec2::new([f64::NAN, -0.0], [f64::NEG_INFINITY, -1.7976931348623157e308]);
    let json = serde_json::to_string(&many).unwrap();
    assert_eq!(json, r#"{"x":["NaN",-0.0],"y":["-inf",-1.7976931348623157e+308]}"#);
    let back: Vec2<[f64; 2]> = serde_json::from_str(&json).unwrap();
    assert!(back.x[0].is_nan() && back.x[1].to_bits() == 0x8000_0000_0000_0000, "{back:?}");
    assert_eq!(back.y, many.y);
    let by_hand: Vec2 = serde_json::from_str(r#"{"x":null,"y":2}"#).unwrap();
    assert!(by_hand.x.is_nan() && by_hand.y == 2.0, "{by_hand:?}");
    let words = Vec2::new("a".to_string(), "inf".to_string());
    assert_eq!(round_trip(&words), words);
    // An optional component: `None` is `null` as always, `Some` of an infinity is not taken for it.
    let optional = Vec2::new(Some(f64::INFINITY), None);
    assert_eq!(serde_json::to_string(&optional).unwrap(), r#"{"x":"inf","y":null}"#);
    assert_eq!(round_trip(&optional), optional);
    let mut bytes = Vec::new();
    ciborium::into_writer(&many, &mut bytes).unwrap();
    let cbor: Vec2<[f64; 2]> = ciborium::from_reader(bytes.as_slice()).unwrap();
    assert!(cbor.x[0].is_nan() && cbor.x[1].to_bits() == 0x8000_0000_0000_0000 && cbor.y == many.y);
}

/// A vector of `f32` reads back from JSON with its non-finite components: serde_json wrote them
/// `null`, which does not read back as an `f32` ("invalid type: null, expected f32"). They are
/// written as an `f64`'s are (`"NaN"`, `"-NaN"`, `"inf"`), and read back with their signs; a
/// finite `f32` is written as it is, its shortest text, and reads back bit for bit, in JSON and in
/// CBOR (which holds the `f32` itself).
#[test]
fn vectors_of_f32_read_back_from_json_with_their_non_finite_components() {
    let nan = f32::NAN;
    for (x, y) in [(nan, 1.5f32), (-nan, f32::INFINITY), (f32::NEG_INFINITY, -0.0), (0.1, f32::MAX)] {
        let v = Vec2::new(x, y);
        let json = serde_json::to_string(&v).unwrap();
        let back: Vec2<f32> = serde_json::from_str(&json).unwrap_or_else(|e| panic!("{json}: {e}"));
        assert_eq!((back.x.to_bits(), back.y.to_bits()), (x.to_bits(), y.to_bits()), "{json}: {back:?}");
        let mut bytes = Vec::new();
        ciborium::into_writer(&v, &mut bytes).unwrap();
        let cbor: Vec2<f32> = ciborium::from_reader(bytes.as_slice()).unwrap();
        assert_eq!((cbor.x.to_bits(), cbor.y.to_bits()), (x.to_bits(), y.to_bits()), "{cbor:?}");
    }
    assert_eq!(serde_json::to_string(&Vec2::new(f32::NAN, 0.1f32)).unwrap(), r#"{"x":"NaN","y":0.1}"#);
}

/// `value` reads back from JSON and from CBOR with its numbers (`numbers` lists them) bit for
/// bit. `name` says which row of the table failed.
fn assert_numbers_round_trip<T: Serialize + DeserializeOwned>(name: &str, value: &T, numbers: fn(&T) -> Vec<f64>) {
    let bits: Vec<u64> = numbers(value).iter().map(|v| v.to_bits()).collect();
    let json = serde_json::to_string(value).unwrap();
    let back: T = serde_json::from_str(&json).unwrap_or_else(|e| panic!("{name}: {json} does not read back: {e}"));
    for (v, &b) in numbers(&back).iter().zip(&bits) {
        assert!(is_edge(*v, b), "{name}: {v:e} for {b:#x}: {json}");
    }
    let mut cbor = Vec::new();
    ciborium::into_writer(value, &mut cbor).unwrap();
    let back: T = ciborium::from_reader(cbor.as_slice()).unwrap_or_else(|e| panic!("{name}: CBOR: {e}"));
    let read: Vec<u64> = numbers(&back).iter().map(|v| v.to_bits()).collect();
    assert_eq!(read, bits, "{name}: CBOR of {json}");
}

/// The types of the runtime that serialize (feature `serde`) numbers of their own fields (not
/// through a type tested above), one row each: with NaN, the infinities, a negative zero and
/// subnormals in each of their numbers, they read back from JSON and CBOR bit for bit. JSON
/// wrote their non-finite numbers as `null`, which did not read back ("invalid type: null,
/// expected f64"), or, for the optional `Constraints::max_error`, read back as `None`.
#[test]
fn every_type_with_numbers_reads_back_its_edge_values() {
    use kinloop_runtime::SolveReport;
    use kinloop_runtime::synthesis::{
        Channel, Constraints, DeConfig, LinkRatioBound, LocalConfig, PlacementBounds, Search, Task, Timing,
        TransmissionBound, Variable,
    };
    // Each start puts every edge value in every number at least once.
    for start in 0..EDGES.len() {
        let e = |k: usize| EDGES[(k + start) % EDGES.len()].0;
        assert_numbers_round_trip("SolveReport", &SolveReport::given(e(0)), |r| vec![r.residual]);
        let mut newton = NewtonConfig::default();
        (newton.residual_tol, newton.step_tol, newton.singular_tol, newton.min_damping) = (e(0), e(1), e(2), e(3));
        assert_numbers_round_trip("NewtonConfig", &newton, |n| {
            vec![n.residual_tol, n.step_tol, n.singular_tol, n.min_damping]
        });
        let mut trace = TraceConfig::default();
        trace.ds = e(0);
        assert_numbers_round_trip("TraceConfig", &trace, |t| vec![t.ds]);
        let mut sweep = SweepConfig::default();
        (sweep.max_step, sweep.corrector_rel, sweep.corrector_abs, sweep.singular_pivot) = (e(0), e(1), e(2), e(3));
        assert_numbers_round_trip("SweepConfig", &sweep, |s| {
            vec![s.max_step, s.corrector_rel, s.corrector_abs, s.singular_pivot]
        });
        let event = Event { kind: EventKind::Kink, x: vec![e(0), e(1)], tau: e(2), q: vec![e(3), e(4)], block: None };
        assert_numbers_round_trip("Event", &event, |v| [v.x.clone(), vec![v.tau], v.q.clone()].concat());
        let constraints = Constraints {
            transmission: Some(TransmissionBound { coupler: "b".into(), follower: "c".into(), min: e(0) }),
            link_ratio: Some(LinkRatioBound { links: vec!["a".into()], max: e(1) }),
            max_error: Some(e(2)),
            ..Constraints::default()
        };
        assert_numbers_round_trip("Constraints", &constraints, |c| {
            vec![
                c.transmission.as_ref().unwrap().min,
                c.link_ratio.as_ref().unwrap().max,
                c.max_error.expect("max_error read back"),
            ]
        });
        let mut local = LocalConfig::default();
        (local.tol, local.step_tol, local.lambda) = (e(0), e(1), e(2));
        assert_numbers_round_trip("LocalConfig", &local, |l| vec![l.tol, l.step_tol, l.lambda]);
        let mut search = Search::default();
        (search.seeds, search.distinct) = (vec![vec![e(0), e(1)], vec![e(2)]], e(3));
        assert_numbers_round_trip("Search", &search, |s| [s.seeds.concat(), vec![s.distinct]].concat());
        let mut de = DeConfig::default();
        (de.f, de.cr) = (e(0), e(1));
        assert_numbers_round_trip("DeConfig", &de, |d| vec![d.f, d.cr]);
        assert_numbers_round_trip("Variable", &Variable::new("a", e(0), e(1)), |v| vec![v.lo, v.hi]);
        let mut task = Task::new(vec![Channel::Value("x".into())], vec![vec![e(0)], vec![e(1)]]);
        task.weights = vec![e(2)];
        task.timing = Timing::Prescribed(vec![vec![e(3)], vec![e(4)]]);
        task.placement =
            Some(PlacementBounds { dx: (e(5), e(6)), dy: (e(7), e(8)), angle: (e(9), e(10)), scale: (e(11), e(12)) });
        assert_numbers_round_trip("Task", &task, |t| {
            let Timing::Prescribed(inputs) = &t.timing else { panic!("{t:?}") };
            let p = t.placement.as_ref().unwrap();
            let placement = [p.dx, p.dy, p.angle, p.scale].into_iter().flat_map(|(lo, hi)| [lo, hi]);
            [t.targets.concat(), t.weights.clone(), inputs.concat(), placement.collect()].concat()
        });
        let free = Timing::Free { lo: e(0), hi: e(1) };
        assert_numbers_round_trip("Timing::Free", &free, |t| match t {
            Timing::Free { lo, hi } => vec![*lo, *hi],
            other => panic!("{other:?}"),
        });
    }
}

/// A NaN reads back from JSON with its bits: the sign bit that arithmetic leaves on it (on
/// x86-64 `0.0 / 0.0` is `0xfff8000000000000`), and any payload. Every NaN was written `"NaN"`
/// (as Rust prints any NaN), which read back as `f64::NAN` with its sign bit cleared: a NaN a
/// computation made did not come back bit for bit, as the states' and vectors' documentation
/// says every number does. Through a vector, a state, a table and an event, which each write
/// numbers their own way; `f64::NAN` is written `"NaN"` as before, and a text of that form whose
/// bits are not a NaN's, or not sixteen hex digits, is refused.
#[test]
fn a_nan_reads_back_from_json_with_its_sign_and_payload() {
    use kinloop_runtime::{Health, Kin, SolveReport};
    let computed = std::hint::black_box(0.0f64) / std::hint::black_box(0.0f64);
    let nans: [(f64, &str); 6] = [
        (f64::NAN, r#""NaN""#),
        (f64::from_bits(0xfff8_0000_0000_0000), r#""-NaN""#),
        (computed, if computed.is_sign_negative() { r#""-NaN""# } else { r#""NaN""# }),
        (f64::from_bits(0x7ff0_0000_0000_0001), r#""NaN(0x7ff0000000000001)""#),
        (f64::from_bits(0xfff4_0000_dead_beef), r#""NaN(0xfff40000deadbeef)""#),
        (f64::from_bits(0x7fff_ffff_ffff_ffff), r#""NaN(0x7fffffffffffffff)""#),
    ];
    for (nan, text) in nans {
        let bits = nan.to_bits();
        let v = Vec2::new(nan, 1.0);
        let json = serde_json::to_string(&v).unwrap();
        let back: Vec2 = serde_json::from_str(&json).unwrap();
        assert_eq!(back.x.to_bits(), bits, "{json}");
        assert_eq!(json, format!(r#"{{"x":{text},"y":1.0}}"#));
        let k = Kin::<1, 1, 0> {
            x: [nan],
            q: [nan],
            dq: [[nan]],
            d2q: [[[nan]]],
            out: [],
            dout: [],
            d2out: [],
            report: SolveReport::given(nan),
            health: Health::default(),
        };
        let json = serde_json::to_string(&k).unwrap();
        let back: Kin<1, 1, 0> = serde_json::from_str(&json).unwrap();
        let read = [back.x[0], back.q[0], back.dq[0][0], back.d2q[0][0][0], back.report.residual];
        assert!(read.iter().all(|r| r.to_bits() == bits), "{json}: {read:?}");
        let mut t = Table::new(vec!["v".into()]);
        t.push(vec![nan]);
        let json = serde_json::to_string(&t).unwrap();
        let back: Table = serde_json::from_str(&json).unwrap();
        assert_eq!(back.rows[0][0].to_bits(), bits, "{json}");
        let e = Event { kind: EventKind::Kink, x: vec![nan], tau: nan, q: vec![nan], block: None };
        let json = serde_json::to_string(&e).unwrap();
        let back: Event = serde_json::from_str(&json).unwrap();
        assert!([back.x[0], back.tau, back.q[0]].iter().all(|r| r.to_bits() == bits), "{json}");
    }
    // The bits of a number, not a NaN's, too few or too many digits, a sign among them: refused.
    for text in ["NaN(0x3ff0000000000000)", "NaN(0x7ff0000000000000)", "NaN(0x7ff8)", "NaN(0x07ff80000000000000)"]
        .into_iter()
        .chain(["NaN(0x+7ff800000000001)", "NaN(7ff8000000000001)", "NaN(0x7ff8000000000001"])
    {
        let json = format!(r#"{{"x":"{text}","y":1.0}}"#);
        let err = serde_json::from_str::<Vec2>(&json).unwrap_err().to_string();
        assert!(err.contains(r#"expected a number, "inf", "-inf", "NaN", or null for NaN"#), "{json}: {err}");
    }
}

/// A decimal too large for `f64` written as a string (`"1e400"`, by hand: kinloop writes only
/// the non-finite numbers as strings) is refused, saying what a number may be written as, as
/// serde_json refuses it written as a number ("number out of range"): it was read as an
/// infinity, a value nobody wrote. The infinities by name, in any case and with either sign,
/// and a finite decimal as a string still read as they are.
#[test]
fn a_decimal_beyond_the_range_of_f64_in_a_string_is_refused() {
    let read = |x: &str| serde_json::from_str::<Vec2>(&format!(r#"{{"x":{x},"y":1.0}}"#)).map(|v| v.x);
    for huge in [r#""1e400""#, r#""-1e400""#, r#""1.8e308""#, r#""+2e308""#] {
        let err = read(huge).expect_err(huge).to_string();
        assert!(err.contains(r#"expected a number, "inf", "-inf", "NaN", or null for NaN"#), "{huge}: {err}");
    }
    assert!(read("1e400").unwrap_err().to_string().contains("number out of range"));
    for (word, value) in [
        (r#""inf""#, f64::INFINITY),
        (r#""-inf""#, f64::NEG_INFINITY),
        (r#""+Infinity""#, f64::INFINITY),
        (r#""-INF""#, f64::NEG_INFINITY),
        (r#""1.7976931348623157e308""#, f64::MAX),
        (r#""0.5""#, 0.5),
    ] {
        assert_eq!(read(word).unwrap(), value, "{word}");
    }
}
