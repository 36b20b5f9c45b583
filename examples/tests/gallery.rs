//! The README's gallery as committed: every image link resolves, every figure under
//! `docs/figures` is shown, and each figure reads at a glance: axis titles name their unit (no
//! placeholder), angle axes are in degrees ticked in divisions of a turn (every 90 degrees over
//! a whole turn), legends sit beside the plot area (never on the data), and curves keep
//! fractional coordinates (no pixel staircase). The figures are parsed back from the SVG files
//! themselves.

use std::path::{Path, PathBuf};

/// The workspace root (the examples package is one level below it).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the examples package sits in the workspace").to_path_buf()
}

/// Targets of the Markdown image links `![alt](target)` in `text`.
fn image_links(text: &str) -> Vec<String> {
    text.split("![")
        .skip(1)
        .filter_map(|rest| rest.split_once("](").and_then(|(_, tail)| tail.split_once(')')).map(|(t, _)| t.to_string()))
        .collect()
}

/// Every `.svg` file below `dir`, as paths relative to the workspace root.
fn svg_files(dir: &Path, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).expect("readable figure folder").map(|e| e.expect("folder entry")) {
        let path = entry.path();
        if path.is_dir() {
            svg_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "svg") {
            let relative = path.strip_prefix(root()).expect("below the root");
            out.push(relative.to_string_lossy().replace('\\', "/"));
        }
    }
}

/// The gallery's figures (sorted).
fn figures() -> Vec<String> {
    let mut all = Vec::new();
    svg_files(&root().join("docs/figures"), &mut all);
    all.sort();
    all
}

/// The value of attribute `name` in the element text `element`.
fn attr(element: &str, name: &str) -> Option<f64> {
    let start = element.find(&format!(" {name}=\""))? + name.len() + 3;
    element[start..].split('"').next()?.parse().ok()
}

/// The opening tags of the elements `<tag class="class"...>` in `svg`.
fn elements<'a>(svg: &'a str, tag: &str, class: &str) -> Vec<&'a str> {
    let open = format!("<{tag} class=\"{class}\"");
    svg.match_indices(&open).map(|(i, _)| &svg[i..i + svg[i..].find('>').expect("closed tag")]).collect()
}

/// The texts of the `<text class="class">` elements in `svg`.
fn texts<'a>(svg: &'a str, class: &str) -> Vec<&'a str> {
    let open = format!("<text class=\"{class}\"");
    svg.match_indices(&open)
        .map(|(i, _)| {
            let body = &svg[i..];
            let start = body.find('>').expect("closed tag") + 1;
            &body[start..start + body[start..].find("</text>").expect("closed text")]
        })
        .collect()
}

#[test]
fn every_gallery_link_resolves_and_every_figure_is_shown() {
    let readme = std::fs::read_to_string(root().join("README.md")).expect("README.md");
    let links = image_links(&readme);
    let broken: Vec<_> = links.iter().filter(|l| !root().join(l).is_file()).collect();
    assert!(broken.is_empty(), "README image links without a file: {broken:?}");
    let figures = figures();
    assert!(figures.len() >= 10, "the gallery has its figures: {figures:?}");
    let unshown: Vec<_> = figures.iter().filter(|f| !links.contains(f)).collect();
    assert!(unshown.is_empty(), "figures not shown in the README (stale?): {unshown:?}");
}

/// Whether an axis title ends in a real unit: `"name [unit]"`, the unit not a placeholder, and
/// only one (an axis mixing units, `"amplitude [N], [Nm]"`, has none that holds for it).
fn has_unit(title: &str) -> bool {
    let split = title.strip_suffix(']').and_then(|t| t.rsplit_once(" ["));
    split.is_some_and(|(name, u)| !name.contains('[') && !["", "length", "analog", "deg", "rad"].contains(&u))
}

/// The numbers of tick labels.
fn ticks(svg: &str, axis: &str) -> Vec<f64> {
    texts(svg, &format!("tick-label {axis}")).iter().map(|t| t.parse().expect("numeric tick label")).collect()
}

/// Checks the ticks of an angle axis: steps of whole degrees that divide a right angle (or are
/// multiples of it), and over a turn or more, multiples of 90.
fn check_angle_ticks(figure: &str, values: &[f64]) {
    let (Some(&first), Some(&last)) = (values.first(), values.last()) else { return };
    if values.len() > 1 {
        let step = values[1] - values[0];
        let divides_turn = step.fract() == 0.0 && (90.0 % step == 0.0 || step % 90.0 == 0.0);
        assert!(step < 1.0 || divides_turn, "{figure}: angle ticks in divisions of a turn: {values:?}");
    }
    if last - first >= 360.0 {
        assert!(values.iter().all(|v| v % 90.0 == 0.0), "{figure}: a turn is ticked every 90°: {values:?}");
    }
}

/// The checks of one panel (`<g class="panel">` ... up to the next): its y axis and legend.
fn check_panel(figure: &str, panel: &str, x_is_angle: bool) {
    let area = elements(panel, "rect", "plot-area");
    assert_eq!(area.len(), 1, "{figure}: one plot area per panel");
    let right = attr(area[0], "x").expect("x") + attr(area[0], "width").expect("width");
    for legend in elements(panel, "rect", "legend-box") {
        assert!(attr(legend, "x").expect("x") > right, "{figure}: the legend is beside the plot area, off the data");
    }
    let y_title = texts(panel, "axis-title y");
    assert_eq!(y_title.len(), 1, "{figure}: one y axis title per panel");
    assert!(has_unit(y_title[0]), "{figure}: y axis `{}` names its unit", y_title[0]);
    if y_title[0].ends_with("[°]") {
        check_angle_ticks(figure, &ticks(panel, "y"));
    }
    if x_is_angle {
        check_angle_ticks(figure, &ticks(panel, "x"));
    }
}

/// Share of the points of a path's `d` attribute off the whole-pixel grid (a coordinate with
/// a fraction).
fn fractional_share(path: &str) -> f64 {
    let d = &path[path.find(" d=\"").expect("a path has d") + 4..];
    let d = &d[..d.find('"').expect("closed d")];
    let points: Vec<&str> = d.split(['M', 'L']).map(str::trim).filter(|p| !p.is_empty()).collect();
    points.iter().filter(|p| p.contains('.')).count() as f64 / points.len().max(1) as f64
}

#[test]
fn every_figure_reads_at_a_glance() {
    for figure in figures() {
        let svg = std::fs::read_to_string(root().join(&figure)).expect("figure file");
        let x_title = texts(&svg, "axis-title x");
        assert_eq!(x_title.len(), 1, "{figure}: a figure of kinloop::plot with one x axis title");
        assert!(has_unit(x_title[0]), "{figure}: x axis `{}` names its unit", x_title[0]);
        let x_is_angle = x_title[0].ends_with("[°]");
        let panels: Vec<&str> = svg.split("<g class=\"panel\">").skip(1).collect();
        assert!(!panels.is_empty(), "{figure}: has a panel");
        for panel in panels {
            check_panel(&figure, panel, x_is_angle);
        }
        // Smooth curves: most points of a long curve are off the pixel grid (a curve snapped to
        // whole pixels has none). Short polylines (a linkage drawn at one position) are exempt.
        for path in elements(&svg, "path", "curve").into_iter().filter(|p| p.matches(" L").count() > 50) {
            assert!(fractional_share(path) > 0.5, "{figure}: a curve snapped to whole pixels");
        }
    }
}

#[test]
fn the_checks_catch_the_old_gallerys_defects() {
    // Placeholder units and unitless titles of the old charts.
    for title in ["position [length]", "analog", "crank angle phi1 [deg]", "|v_qS|", "amplitude [N], [Nm]"] {
        assert!(!has_unit(title), "{title}");
    }
    assert!(has_unit("crank angle φ1 [°]") && has_unit("x' [units of r/rad]"));
    // A turn ticked 0, 50, 100, ... instead of every 90 degrees.
    let fifty: Vec<f64> = (0..=7).map(|k| 50.0 * k as f64).collect();
    assert!(std::panic::catch_unwind(|| check_angle_ticks("old", &fifty)).is_err());
    check_angle_ticks("new", &[0.0, 90.0, 180.0, 270.0, 360.0]);
    // A staircase on whole pixels, and a smooth curve.
    assert_eq!(fractional_share(r#"<path class="curve" d="M1,2 L1,3 L2,3""#), 0.0);
    assert_eq!(fractional_share(r#"<path class="curve" d="M1.5,2 L1.25,3.75""#), 1.0);
    // A legend drawn over the plot area.
    let on_data = r#"<rect class="plot-area" x="96" y="48" width="600" height="250"/><text class="axis-title y">y [mm]</text><rect class="legend-box" x="500" y="60"/>"#;
    assert!(std::panic::catch_unwind(|| check_panel("old", on_data, false)).is_err());
}
