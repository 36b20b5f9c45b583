//! `kinloop` end to end: the built binary on the shipped `.kl` files, its CSV parsed and
//! compared with the compiled mechanisms of the same declarations (kinloop's fixtures), its
//! diagnostics and exit codes.

use kinloop::Mechanism;
use kinloop_fixtures as fx;
use std::path::PathBuf;
use std::process::{Command, Output};

fn kinloop(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_kinloop")).args(args).output().expect("the kinloop binary runs")
}

fn shipped(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("mechanisms").join(name).display().to_string()
}

/// The CSV's header and rows.
fn csv(out: &Output) -> (Vec<String>, Vec<Vec<f64>>) {
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout.clone()).expect("utf-8");
    let mut lines = text.lines();
    let header = lines.next().expect("header").split(',').map(str::to_string).collect();
    let rows = lines.map(|l| l.split(',').map(|v| v.parse().expect("a number")).collect()).collect();
    (header, rows)
}

fn column(header: &[String], name: &str) -> usize {
    header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

/// The shipped files hold the fixtures' declarations: the same tokens.
#[test]
fn shipped_files_are_the_fixtures_declarations() {
    // `stringify!` writes doc comments as raw strings, the lexer as plain ones: the same text.
    let tokens = |t: &str| t.parse::<proc_macro2::TokenStream>().expect("tokens").to_string().replace("= r\"", "= \"");
    let rhombic = fx::RHOMBIC_DRIVE_TEXT.to_string();
    for (file, text) in [("four_bar.kl", fx::FOUR_BAR_TEXT), ("rhombic_drive.kl", rhombic.as_str())] {
        let shipped = std::fs::read_to_string(shipped(file)).expect("shipped file");
        assert_eq!(tokens(&shipped), tokens(text), "{file}");
    }
}

#[test]
fn solve_writes_the_compiled_mechanisms_state() {
    let drive = fx::RhombicDrive::default();
    let inputs = [0.0, 0.7, -2.0, 3.0];
    let mut args = vec!["solve".to_string(), shipped("rhombic_drive.kl")];
    for x in inputs {
        args.extend(["--at".to_string(), x.to_string()]);
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (header, rows) = csv(&kinloop(&args));
    assert_eq!(header[0], "phi1 [rad]");
    assert_eq!(rows.len(), inputs.len());
    let cfg = kinloop::NewtonConfig::default();
    for (x, row) in inputs.iter().zip(&rows) {
        let k = drive.kinematics_flat(&[*x], &drive.guess_flat(&[*x]), &cfg).expect("compiled solve");
        // Written with the shortest representation that reads back exactly: equal bits.
        assert_eq!(row[column(&header, "x_c [length unit]")], k.q[2]);
        assert_eq!(row[column(&header, "d(phi2)/d(phi1) [rad/rad]")], k.dq[0][0]);
        assert_eq!(row[column(&header, "d2(x_f)/d(phi1)^2 [length unit/rad^2]")], k.d2q[3][0][0]);
        assert_eq!(row[column(&header, "gap [length unit]")], k.out[6]);
    }
}

#[test]
fn degrees_and_parameters() {
    let (a, b, c, d) = (1.2, 3.0, 2.5, 3.2);
    let four_bar = fx::FourBar { a, b, c, d };
    let params = format!("a={a},b={b},c={c},d={d}");
    let (header, rows) = csv(&kinloop(&["solve", &shipped("four_bar.kl"), "--at", "30", "--deg", "--params", &params]));
    let x = 30f64.to_radians();
    let k = four_bar.kinematics_flat(&[x], &four_bar.guess_flat(&[x]), &Default::default()).expect("solve");
    // Degrees: one conversion and one rounding each.
    let close = |got: f64, want: f64| assert!((got - want).abs() <= 4.0 * f64::EPSILON * want.abs(), "{got} vs {want}");
    close(row_of(&header, &rows, "beta [deg]"), k.q[0].to_degrees());
    close(
        row_of(&header, &rows, "d2(gamma)/d(phi)^2 [deg/deg^2]"),
        k.d2q[1][0][0].to_degrees() / 180f64.to_degrees() * std::f64::consts::PI,
    );
    close(row_of(&header, &rows, "d(pc.y)/d(phi) [length unit/deg]"), k.dout[1][0].to_radians());
}

fn row_of(header: &[String], rows: &[Vec<f64>], name: &str) -> f64 {
    rows[0][column(header, name)]
}

#[test]
fn check_reports_the_structure() {
    let out = kinloop(&["check", &shipped("rhombic_drive.kl")]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with(fx::RhombicDrive::DECOMPOSITION), "{text}");
    assert!(text.contains("x_c [length unit]"), "{text}");
}

#[test]
fn errors_have_carets_and_exit_codes() {
    let dir = std::env::temp_dir().join(format!("kinloop-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let bad = dir.join("bad.kl");
    std::fs::write(
        &bad,
        "pub struct S {\n    params r = 1;\n    input phi;\n    unknowns x = 1;\n    eq e: x == r * phy;\n}\n",
    )
    .expect("write");
    let out = kinloop(&["check", &bad.display().to_string()]);
    assert_eq!(out.status.code(), Some(65));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("error: unknown name `phy`"), "{err}");
    assert!(err.contains("bad.kl:5:20"), "{err}");
    assert!(err.contains("^^^"), "{err}");

    let missing = kinloop(&["check", &dir.join("missing.kl").display().to_string()]);
    assert_eq!(missing.status.code(), Some(66));
    let unset = kinloop(&["solve", &shipped("four_bar.kl"), "--at", "0"]);
    assert_eq!(unset.status.code(), Some(1), "{}", String::from_utf8_lossy(&unset.stderr));
    let wrong_param = kinloop(&["solve", &shipped("rhombic_drive.kl"), "--at", "0", "--params", "nope=1"]);
    assert_eq!(wrong_param.status.code(), Some(2));
    let wrong_inputs = kinloop(&["solve", &shipped("rhombic_drive.kl"), "--at", "0,1"]);
    assert_eq!(wrong_inputs.status.code(), Some(2));
    // Out of reach: a crank longer than the rod leaves no assembly at some angle.
    let out_of_reach = kinloop(&["solve", &shipped("rhombic_drive.kl"), "--at", "1.5", "--params", "r_p=5"]);
    assert_eq!(out_of_reach.status.code(), Some(1), "{}", String::from_utf8_lossy(&out_of_reach.stdout));
    std::fs::remove_dir_all(&dir).ok();
}
