//! A table's columns with angles in degrees (`Table::column_deg`): angles, lengths and the
//! analogs of both, against finite differences taken in degrees of the closed forms the
//! table's radians come from.

use kinloop_runtime::{Table, to_deg};

/// Crank radius of `x = R cos(phi)`, in mm.
const R: f64 = 2.5;

/// A length `x` (mm) and an angle `theta` (rad) of the input `phi` (rad), with their first and
/// second derivatives by `phi`: `x = R cos(phi)`, `theta = phi / 2 + 0.3 sin(phi)`.
fn closed_form(phi: f64) -> [f64; 6] {
    let (s, c) = phi.sin_cos();
    [R * c, -R * s, -R * c, phi / 2.0 + 0.3 * s, 0.5 + 0.3 * c, -0.3 * s]
}

/// The same quantities with the angles in degrees, as functions of `phi` in degrees.
fn in_degrees(phi_deg: f64) -> (f64, f64) {
    let [x, _, _, theta, _, _] = closed_form(phi_deg.to_radians());
    (x, theta.to_degrees())
}

/// Central first and second differences of `f` at `a` with step `h`.
fn differences(f: impl Fn(f64) -> f64, a: f64, h: f64) -> (f64, f64) {
    let (m, z, p) = (f(a - h), f(a), f(a + h));
    ((p - m) / (2.0 * h), (p - 2.0 * z + m) / (h * h))
}

fn close(got: f64, want: f64, rel: f64, what: &str) {
    assert!((got - want).abs() <= rel * want.abs(), "{what}: {got} against {want}");
}

#[test]
fn analogs_of_lengths_and_angles_are_per_degree() {
    let names = ["phi", "x", "d(x)/d(phi)", "d2(x)/d(phi)^2", "theta", "d(theta)/d(phi)", "d2(theta)/d(phi)^2"];
    let mut t = Table::new(names.iter().map(|n| n.to_string()).collect());
    let inputs = [0.4, 1.1, 2.0];
    for phi in inputs {
        let mut row = vec![phi];
        row.extend(closed_form(phi));
        t.push(row);
    }
    let t = t.with_units(&[("phi", "rad"), ("x", "mm"), ("theta", "rad")]);
    let col = |name: &str| t.column_deg(name).unwrap();
    for (k, phi) in inputs.iter().enumerate() {
        let phi_deg = phi.to_degrees();
        // Steps in degrees: the first differences' truncation (h^2 f'''/6) and rounding
        // (eps |f| / h) both below 1e-10 of the values; the second's below 1e-7.
        let (dx, _) = differences(|a| in_degrees(a).0, phi_deg, 1e-3);
        let (_, d2x) = differences(|a| in_degrees(a).0, phi_deg, 0.05);
        let (dth, _) = differences(|a| in_degrees(a).1, phi_deg, 1e-3);
        let (_, d2th) = differences(|a| in_degrees(a).1, phi_deg, 0.05);
        close(col("phi")[k], phi_deg, 1e-15, "phi");
        // A length is a length whatever the unit of angles.
        assert_eq!(col("x")[k], t.column("x").unwrap()[k]);
        close(col("d(x)/d(phi)")[k], dx, 1e-9, "d(x)/d(phi) in mm/deg");
        close(col("d2(x)/d(phi)^2")[k], d2x, 1e-6, "d2(x)/d(phi)^2 in mm/deg^2");
        close(col("theta")[k], in_degrees(phi_deg).1, 1e-15, "theta");
        // deg/deg is rad/rad: unchanged.
        close(col("d(theta)/d(phi)")[k], dth, 1e-9, "d(theta)/d(phi) in deg/deg");
        assert_eq!(col("d(theta)/d(phi)")[k], t.column("d(theta)/d(phi)").unwrap()[k]);
        close(col("d2(theta)/d(phi)^2")[k], d2th, 1e-6, "d2(theta)/d(phi)^2 in deg/deg^2");
    }
}

/// An analog by a length input: an angle per length is in degrees per length, times `180/pi`;
/// a length per length is unchanged. Without units the column is taken to be an angle.
#[test]
fn analogs_by_a_length_input_and_columns_of_unknown_unit() {
    let mut t = Table::new(vec!["s".into(), "psi".into(), "d(psi)/d(s)".into(), "d(y)/d(s)".into(), "y".into()]);
    t.push(vec![3.0, 0.5, 0.25, -2.0, 1.0]);
    let plain = t.clone();
    let t = t.with_units(&[("s", "mm"), ("psi", "rad"), ("y", "mm")]);
    assert_eq!(t.column_deg("d(psi)/d(s)"), Some(vec![to_deg(0.25)]));
    assert_eq!(t.column_deg("d(y)/d(s)"), Some(vec![-2.0]));
    assert_eq!(t.column_deg("s"), Some(vec![3.0]));
    assert_eq!(plain.column_deg("psi"), Some(vec![to_deg(0.5)]));
    assert_eq!(t.column_deg("nothing"), None);
}
