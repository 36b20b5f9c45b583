//! The committed gallery is what the code draws: every animation in `docs/animations` and every
//! page in `docs/pages` is what the `animations` example writes now, and neither folder holds a
//! file the example no longer writes. A change to a drawing (its layout, its notes, a
//! mechanism's fixture) then fails here until the gallery is regenerated, rather than leaving the
//! README showing an older picture.
//!
//! The drawings are deterministic, so on the platform that wrote them they are equal byte for
//! byte. Another platform's libm may differ in a last bit, which can move a number written in
//! full precision by an ulp, or one rounded to 0.1 px across a rounding boundary; so the text
//! between the numbers must be equal, and each number equal to within one unit of its last
//! written digit (or 1e-9 of itself). A drawing that changed moves far more than that.

// The example's own functions, so that what is compared is what it writes (its `main` is not
// called here).
#[allow(dead_code)]
#[path = "../animations.rs"]
mod animations;

use std::path::{Path, PathBuf};

/// The workspace root (the examples package is one level below it).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the examples package sits in the workspace").to_path_buf()
}

/// `text` cut into the pieces between its numbers and its numbers (unsigned decimals, with an
/// exponent where one is written): `"M1.5,-2e-3"` gives `["M", ",-", ""]` and `["1.5", "2e-3"]`.
fn split_numbers(text: &str) -> (Vec<&str>, Vec<&str>) {
    let (bytes, mut between, mut numbers, mut from, mut i) = (text.as_bytes(), Vec::new(), Vec::new(), 0, 0);
    let digits = |mut k: usize| {
        while k < bytes.len() && bytes[k].is_ascii_digit() {
            k += 1;
        }
        k
    };
    while i < bytes.len() {
        if !bytes[i].is_ascii_digit() {
            i += 1;
            continue;
        }
        let start = i;
        i = digits(i);
        if i + 1 < bytes.len() && bytes[i] == b'.' && bytes[i + 1].is_ascii_digit() {
            i = digits(i + 1);
        }
        let sign = usize::from(i + 1 < bytes.len() && bytes[i] == b'e' && bytes[i + 1] == b'-');
        if i + 1 + sign < bytes.len() && bytes[i] == b'e' && bytes[i + 1 + sign].is_ascii_digit() {
            i = digits(i + 1 + sign);
        }
        between.push(&text[from..start]);
        numbers.push(&text[start..i]);
        from = i;
    }
    between.push(&text[from..]);
    (between, numbers)
}

/// One unit of the last digit written in the number `n` (`"394.45"` -> 0.01, `"2e-3"` -> 1e-3).
fn last_digit(n: &str) -> f64 {
    let (mantissa, exponent) = n.split_once('e').map_or((n, 0), |(m, e)| (m, e.parse::<i32>().expect("exponent")));
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len() as i32);
    10f64.powi(exponent - decimals)
}

/// Whether `written` is the drawing `drawn`: the same text between the numbers, and each number
/// within one unit of its last written digit, or 1e-9 of itself (see the module's comment).
fn same_drawing(written: &str, drawn: &str) -> bool {
    let ((a_text, a), (b_text, b)) = (split_numbers(written), split_numbers(drawn));
    a_text == b_text
        && a.iter().zip(&b).all(|(x, y)| {
            let (u, v): (f64, f64) = (x.parse().expect("a number"), y.parse().expect("a number"));
            (u - v).abs() <= last_digit(x).max(last_digit(y)) * (1.0 + 1e-9)
                || (u - v).abs() <= 1e-9 * u.abs().max(v.abs())
        })
}

/// The files of `folder` whose contents differ from what the example writes, and the files in
/// it the example does not write (stale leftovers), each named.
fn stale(folder: &Path, files: &[(String, String)]) -> Vec<String> {
    let mut found = Vec::new();
    for (name, text) in files {
        // A checkout that turned line ends into CRLF has not changed the drawing.
        match std::fs::read_to_string(folder.join(name)) {
            Ok(committed) if same_drawing(&committed.replace("\r\n", "\n"), text) => {}
            Ok(_) => found.push(format!("{name} differs")),
            Err(e) => found.push(format!("{name} missing ({e})")),
        }
    }
    for entry in std::fs::read_dir(folder).expect("a gallery folder") {
        let name = entry.expect("a folder entry").file_name().to_string_lossy().into_owned();
        if !files.iter().any(|(n, _)| *n == name) {
            found.push(format!("{name} is written by nothing"));
        }
    }
    found
}

#[test]
fn the_committed_gallery_is_what_the_example_draws() -> Result<(), Box<dyn std::error::Error>> {
    let (drawn, pages) = (animations::animations()?, animations::pages()?);
    // One animation and one page per mechanism (exposures besides): what the README shows.
    assert!(drawn.len() >= 11 && pages.len() >= 11, "{} animations, {} pages", drawn.len(), pages.len());
    let mut found = stale(&root().join("docs/animations"), &drawn);
    found.extend(stale(&root().join("docs/pages"), &pages));
    assert!(
        found.is_empty(),
        "the committed gallery is not what the code draws: {found:?}; regenerate it with \
         `cargo run --release -p kinloop-examples --example animations -- docs/animations`"
    );
    Ok(())
}

/// The comparison sees a changed drawing, a missing file and a leftover one.
#[test]
fn the_comparison_sees_a_stale_file() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("gallery-check");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("a.svg"), "<svg/>\n").unwrap();
    std::fs::write(dir.join("old.svg"), "<svg/>").unwrap();
    let files = [("a.svg".to_string(), "<svg width=\"2\"/>\n".to_string()), ("b.svg".to_string(), String::new())];
    let mut found = stale(&dir, &files);
    found.sort();
    assert_eq!(found.len(), 3, "{found:?}");
    assert!(
        found[0] == "a.svg differs"
            && found[1].starts_with("b.svg missing")
            && found[2] == "old.svg is written by nothing"
    );
    // A number one unit of its last digit off (another libm's last bit, rounded) is the same
    // drawing; two units off, or the text around the numbers changed, is not.
    assert!(same_drawing(
        r#"<svg width="360.1" data-scale="2.4364906775195303">"#,
        r#"<svg width="360.2" data-scale="2.4364906775195307">"#
    ));
    assert!(!same_drawing(r#"<svg width="360.1">"#, r#"<svg width="360.3">"#));
    assert!(!same_drawing(r#"<svg width="556" height="617">"#, r#"<svg width="360.1" height="634">"#));
    assert!(!same_drawing("<text>by inversion</text>", "<text>by</text><text>inversion</text>"));
    assert_eq!(split_numbers("M1.5,-2e-3 L7e2x"), (vec!["M", ",-", " L", "x"], vec!["1.5", "2e-3", "7e2"]));
    assert_eq!([last_digit("394.45"), last_digit("2e-3"), last_digit("12")], [0.01, 1e-3, 1.0]);
    // The same text with CRLF line ends is the same drawing.
    std::fs::write(dir.join("a.svg"), "<svg width=\"2\"/>\r\n").unwrap();
    std::fs::remove_file(dir.join("old.svg")).unwrap();
    assert_eq!(stale(&dir, &files[..1]), Vec::<String>::new());
    std::fs::remove_dir_all(&dir).unwrap();
}
