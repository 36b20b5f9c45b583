//! The kind of quantity `mechanism!` infers for every column (angle, length, dimensionless, or
//! not inferred), and the units it puts into a table's CSV header, read back with the `csv`
//! crate (not the runtime's reader).

use kinloop::QuantityKind::{Angle, Dimensionless, Length, Other};
use kinloop::{Mechanism, Table};
use kinloop_fixtures::cam_linkage::DwellCamRocker;
use kinloop_fixtures::roller_edger::RollerEdger;
use kinloop_fixtures::{FiveBar, RhombicDrive};
use std::collections::HashMap;

kinloop::mechanism! {
    /// A slider at `u l` along a rod turned by `phi`, and outputs of each kind.
    pub struct Kinds {
        params l = 2.0, h = 0.5, k = 3.0;
        input phi;
        unknowns u = 0.5, y = 1.0;
        loop rod: u * l @ phi == (h, y);
        output ratio = y / h;
        output angle = atan2(y, h);
        output reach = sqrt(h ^ 2 + y ^ 2);
        output area = h * y;
        output scaled = k * y;
    }
}

kinloop::mechanism! {
    /// A time input inside a sine (`sin(w t)`): `w t` is an angle, but neither factor alone is.
    pub struct Oscillator {
        params w = 2.0, a = 0.5, l = 1.0, h = 2.0;
        input t;
        unknowns y = 0, th = 0, x = h - l;
        eq follow: y == a * sin(w * t);
        loop rod: (x, 0) + l @ th == (h, y);
    }
}

kinloop::mechanism! {
    /// A slider-crank turned by its input less whole turns: `floor` and `wrap` keep the kind of
    /// their argument, as `abs` does; of a pure number, a pure number.
    pub struct Wrapped {
        params r = 1.0, l = 3.0;
        input phi;
        unknowns psi = 0, x = 4.0;
        let t = phi - 2 * pi * floor(phi / (2 * pi));
        loop rod: r @ t == (x, 0) + l @ psi;
        output stroke = wrap(x, l);
        output angle = wrap(phi, 2 * pi);
        output count = floor(3 * sin(phi));
    }
}

kinloop::mechanism! {
    /// A rise of a cam over `rise` from `phi0`, both written in degrees, moving a follower that
    /// swings a rocker: the input never meets a sine, and is an angle because it is compared
    /// with `phi0` (through `wrap`, a difference and `clamp`). `w`, which meets no sine either,
    /// is an angle by its guess in degrees; `z`, a multiple of a ratio, is not inferred.
    pub struct CamRise {
        params lift = 20.0, y0 = 60.0, l = 70.0, c = 40.0, dx = -40.0, dy = 140.0,
               phi0 = deg(30), rise = deg(120), k = 2.0;
        input phi;
        unknowns gamma = 1.6, psi = -0.25, z = 1.0, w = deg(10);
        let u = clamp((wrap(phi, 2 * pi) - phi0) / rise, 0, 1);
        loop rod: (0, y0 + lift * u ^ 2) + l @ gamma == (dx, dy) + c @ psi;
        eq spare: z == k * u ^ 2;
        eq lag: w == phi0 * u ^ 2;
        output lead = phi - phi0;
        output beyond = max(phi, rise);
        output turn = psi - gamma;
    }
}

/// The header of a table's CSV, read by the `csv` crate: column name -> unit.
fn header(t: &Table) -> HashMap<String, String> {
    let mut bytes = Vec::new();
    t.write_csv(&mut bytes).unwrap();
    let mut r = csv::Reader::from_reader(&bytes[..]);
    let fields: Vec<String> = r.headers().unwrap().iter().map(str::to_string).collect();
    assert_eq!(fields.len(), t.columns.len());
    assert_eq!(r.records().count(), t.rows.len());
    fields
        .iter()
        .map(|f| match f.strip_suffix(']').and_then(|f| f.split_once(" [")) {
            Some((name, unit)) => (name.to_string(), unit.to_string()),
            None => (f.clone(), String::new()),
        })
        .collect()
}

#[test]
fn kinds_are_inferred_from_the_declaration() {
    assert_eq!(RhombicDrive::INPUT_KINDS, [Angle]);
    assert_eq!(RhombicDrive::UNKNOWN_KINDS, [Angle, Angle, Length, Length]);
    // Three points (x, y each), then `gap = x_f - x_c`.
    assert_eq!(RhombicDrive::OUTPUT_KINDS, [Length; 7]);
    assert_eq!(FiveBar::INPUT_KINDS, [Angle, Angle]);
    // `spread = phi3 - phi2`: a difference of angles.
    assert_eq!(FiveBar::OUTPUT_KINDS, [Length, Length, Angle]);
    // Time drives the roller edger (`s1 = v1 t`): neither an angle nor a length.
    assert_eq!(RollerEdger::INPUT_KINDS, [Other]);
    assert_eq!(RollerEdger::UNKNOWN_KINDS, [Angle; 4]);
    // `u` multiplies `l`, and neither is inferred (one is a ratio, but nothing says which); `y`
    // and `h` are lengths; the outputs by their expressions; a length plus an angle is nothing
    // kinloop names, nor a length times a parameter whose kind is unknown.
    assert_eq!(Kinds::UNKNOWN_KINDS, [Other, Length]);
    assert_eq!(Kinds::OUTPUT_KINDS, [Dimensionless, Angle, Length, Other, Other]);
    assert_eq!(Oscillator::INPUT_KINDS, [Other]);
    // `y` and `x` are terms of the loop's projections: lengths; `th` turns inside `cos`.
    assert_eq!(Oscillator::UNKNOWN_KINDS, [Length, Angle, Length]);
    // The trait carries the same constants for generic code.
    assert_eq!(<Kinds as Mechanism<2, 1, 5>>::OUTPUT_KINDS, Kinds::OUTPUT_KINDS);
}

/// Values written in degrees are angles, and so is whatever is added to or compared with an
/// angle without a dimension of its own; a ratio of angles and what it multiplies are not
/// guessed.
#[test]
fn angles_written_in_degrees_and_what_is_added_to_them() {
    assert_eq!(CamRise::INPUT_KINDS, [Angle]);
    assert_eq!(CamRise::UNKNOWN_KINDS, [Angle, Angle, Other, Angle]);
    assert_eq!(CamRise::OUTPUT_KINDS, [Angle, Angle, Angle]);
    let m = CamRise::default();
    let states: Vec<_> = m.sweep(0.0, 1.0, 3, &m.guess(0.0)).unwrap().map(Result::unwrap).collect();
    let h = header(&Table::from_states::<CamRise, _, _, _>(states.iter().map(|s| &s.flat)));
    assert_eq!((h["phi"].as_str(), h["psi"].as_str(), h["lead"].as_str()), ("rad", "rad", "rad"));
    // The fixtures' dwell cam, whose law is written so.
    assert_eq!(DwellCamRocker::INPUT_KINDS, [Angle]);
}

#[test]
fn floor_and_wrap_keep_the_kinds() {
    assert_eq!(Wrapped::INPUT_KINDS, [Angle]);
    assert_eq!(Wrapped::UNKNOWN_KINDS, [Angle, Length]);
    assert_eq!(Wrapped::OUTPUT_KINDS, [Length, Angle, Dimensionless]);
}

#[test]
fn csv_headers_carry_the_inferred_units() {
    let m = RhombicDrive::default();
    let states: Vec<_> = m.sweep(0.0, 1.0, 5, &m.guess(0.0)).unwrap().map(Result::unwrap).collect();
    let table = Table::from_states::<RhombicDrive, _, _, _>(states.iter().map(|s| &s.flat));
    let h = header(&table);
    assert_eq!(h["phi1"], "rad");
    assert_eq!(h["phi2"], "rad");
    assert_eq!(h["x_c"], "length unit");
    assert_eq!(h["s2.x"], "length unit");
    assert_eq!(h["gap"], "length unit");
    assert_eq!(h["d(phi2)/d(phi1)"], "rad/rad");
    assert_eq!(h["d(x_c)/d(phi1)"], "length unit/rad");
    assert_eq!(h["d2(x_c)/d(phi1)^2"], "length unit/rad^2");
    assert_eq!(h["d2(s2.y)/d(phi1)^2"], "length unit/rad^2");
    // Naming the unit of length replaces the placeholder everywhere, angles stay radians.
    let h = header(&table.clone().with_length_unit("mm"));
    assert_eq!((h["x_c"].as_str(), h["d(s2.x)/d(phi1)"].as_str(), h["phi2"].as_str()), ("mm", "mm/rad", "rad"));
    // What the table reads back is what it wrote.
    let mut bytes = Vec::new();
    table.write_csv(&mut bytes).unwrap();
    assert_eq!(Table::read_csv(&bytes[..]).unwrap(), table);
}

#[test]
fn units_of_two_inputs_a_time_input_and_overrides() {
    let m = FiveBar::default();
    let table = m.sweep([1.2, 0.8], [1.5, 1.1], 3, &m.guess([1.2, 0.8])).unwrap().table().unwrap();
    let h = header(&table);
    assert_eq!(h["d2(pc.x)/d(th1)d(th2)"], "length unit/rad^2");
    assert_eq!(h["d(spread)/d(th2)"], "rad/rad");
    let m = RollerEdger::default();
    let table = m.sweep(0.0, 1.0, 3, &m.guess(0.0)).unwrap().table().unwrap();
    let h = header(&table);
    // No unit is guessed for an input kinloop cannot classify: it is named as the input's,
    // so that the analogs by it say what they are per (as the command line writes them)...
    assert_eq!(
        (h["t"].as_str(), h["d(phi1)/d(t)"].as_str(), h["d2(phi1)/d(t)^2"].as_str(), h["phi1"].as_str()),
        ("unit of t", "rad/unit of t", "rad/(unit of t)^2", "rad")
    );
    // ... until the user states it; the inferred units stay.
    let h = header(&table.with_units(&[("t", "s")]));
    assert_eq!((h["t"].as_str(), h["d(phi1)/d(t)"].as_str(), h["d2(phi1)/d(t)^2"].as_str()), ("s", "rad/s", "rad/s^2"));
}
