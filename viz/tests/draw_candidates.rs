//! Synthesis candidates drawn over their targets (`draw::candidates`): a small path-generation
//! search for a four-bar whose targets lie on a known design's coupler curve, moved by a known
//! placement; the SVG parsed back as XML. The targets sit at their coordinates (read through
//! the axes' own tick labels), each valid candidate's traced path passes within its reported
//! error of every target, the axes name their unit, the legend ranks the candidates with their
//! errors, and nothing is NaN.

use kinloop::synthesis::{Design, LocalConfig, PlacementBounds, Problem, Search, Task};
use kinloop_viz::draw::{CandidatesConfig, DrawError, HtmlConfig, candidate_page, candidates};
use std::f64::consts::TAU;

kinloop::mechanism! {
    /// Four-bar with a coupler point `p` at `e` from the crank pin, `alpha` off the coupler.
    #[kinloop(sensitivities)]
    pub struct Coupler {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.0, e = 1.5, alpha = 0.6;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point p = a @ phi + e @ (beta + alpha);
    }
}

/// Ticks of one axis: (value, pixel) read from the labels.
fn ticks(doc: &roxmltree::Document, class: &str, attr: &str) -> Vec<(f64, f64)> {
    doc.descendants()
        .filter(|n| n.attribute("class") == Some(class))
        .map(|n| {
            let v: f64 = n.text().unwrap().parse().unwrap();
            let mut p: f64 = n.attribute(attr).unwrap().parse().unwrap();
            if attr == "y" {
                // The label's baseline is 4 px below its tick.
                p -= 4.0;
            }
            (v, p)
        })
        .collect()
}

/// The plane's point of a pixel, through the first and last tick of each axis.
fn world(xt: &[(f64, f64)], yt: &[(f64, f64)], [x, y]: [f64; 2]) -> [f64; 2] {
    let on = |t: &[(f64, f64)], p: f64| {
        let ((v0, p0), (v1, p1)) = (t[0], t[t.len() - 1]);
        v0 + (p - p0) / (p1 - p0) * (v1 - v0)
    };
    [on(xt, x), on(yt, y)]
}

#[test]
fn candidates_are_drawn_through_their_targets_on_axes_with_units() {
    // Ten points of the default design's coupler curve, turned by 0.3 rad and moved by
    // (0.5, -0.4): the search must find a placement too (20 residuals, 20 unknowns).
    let truth = Coupler::default();
    let (dx, dy, turn) = (0.5, -0.4, 0.3f64);
    let targets: Vec<[f64; 2]> = (0..10)
        .map(|k| 0.3 + 0.6 * k as f64)
        .map(|phi| {
            let p = truth.solve(phi).unwrap().out.p;
            let (sn, cs) = turn.sin_cos();
            [dx + cs * p.x - sn * p.y, dy + sn * p.x + cs * p.y]
        })
        .collect();
    let design = Design::new()
        .var("a", 0.6, 1.4)
        .var("b", 2.0, 4.0)
        .var("c", 1.8, 3.2)
        .var("d", 2.0, 4.0)
        .var("e", 0.8, 2.2)
        .var("alpha", 0.0, 1.2);
    let placement = PlacementBounds::translation((-2.0, 2.0), (-2.0, 2.0)).with_rotation((-1.0, 1.0));
    let task = Task::path("p", targets.clone()).untimed(0.0, TAU).with_placement(placement);
    let problem = Problem::new(Coupler::default(), &design, &task).unwrap();
    let search = Search::default()
        .with_starts(0..24)
        .with_seed(3)
        .with_keep(3)
        .with_local(LocalConfig::default().with_max_evaluations(300));
    let report = search.run(&problem).unwrap();
    let best: Vec<_> = report.candidates.iter().take(3).cloned().collect();
    assert!(
        best.iter().any(|c| c.is_valid()),
        "a valid candidate among {:?}",
        best.iter().map(|c| &c.defects).collect::<Vec<_>>()
    );
    let config = CandidatesConfig::new("p").with_title("Best four-bars").with_length_unit("mm");
    let svg = candidates(&Coupler::default(), &best, &targets, &config).unwrap();
    assert!(!svg.contains("NaN") && !svg.contains("inf"));
    // For a person to look at (never committed).
    std::fs::write(std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("candidates.svg"), &svg).unwrap();
    let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
    for node in doc.descendants() {
        for a in node.attributes() {
            if ["x", "y", "cx", "cy", "r", "width", "height", "x1", "x2", "y1", "y2"].contains(&a.name()) {
                assert!(a.value().parse::<f64>().is_ok_and(f64::is_finite), "{}={}", a.name(), a.value());
            }
        }
    }
    let text = |class: &str| {
        doc.descendants().find(|n| n.attribute("class") == Some(class)).and_then(|n| n.text()).unwrap().to_string()
    };
    assert_eq!(text("axis-x"), "x [mm]");
    assert_eq!(text("axis-y"), "y [mm]");
    let (xt, yt) = (ticks(&doc, "tick-x", "x"), ticks(&doc, "tick-y", "y"));
    assert!(xt.len() >= 3 && yt.len() >= 3);
    // One scale on both axes.
    let sx = (xt[xt.len() - 1].1 - xt[0].1) / (xt[xt.len() - 1].0 - xt[0].0);
    let sy = (yt[0].1 - yt[yt.len() - 1].1) / (yt[yt.len() - 1].0 - yt[0].0);
    assert!((sx - sy).abs() <= 0.2 / (xt[xt.len() - 1].0 - xt[0].0).min(yt[yt.len() - 1].0 - yt[0].0), "{sx} vs {sy}");
    // Every pixel is written to 0.1 px (half of it off at most), the ticks too: a point read
    // back through the ticks is within 0.2 px of its place.
    let tol = 0.2 / sx;
    let circles: Vec<(usize, [f64; 2])> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("target"))
        .map(|n| {
            let at = |k: &str| n.attribute(k).unwrap().parse::<f64>().unwrap();
            (n.attribute("data-index").unwrap().parse().unwrap(), world(&xt, &yt, [at("cx"), at("cy")]))
        })
        .collect();
    assert_eq!(circles.len(), targets.len());
    for (i, q) in &circles {
        let t = targets[*i];
        assert!((q[0] - t[0]).abs() <= tol && (q[1] - t[1]).abs() <= tol, "target {i}: {q:?} vs {t:?}");
    }
    let numbers: Vec<String> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("target-label"))
        .map(|n| n.text().unwrap().to_string())
        .collect();
    let expected: Vec<String> = (1..=10).map(|k| k.to_string()).collect();
    assert_eq!(numbers, expected, "numbered in order");
    for (rank, c) in best.iter().enumerate() {
        let path = doc
            .descendants()
            .find(|n| n.attribute("class") == Some("path") && n.attribute("data-rank") == Some(&rank.to_string()))
            .expect("the candidate's path");
        let pts: Vec<[f64; 2]> = path
            .attribute("points")
            .unwrap()
            .split(' ')
            .map(|p| {
                let (x, y) = p.split_once(',').unwrap();
                world(&xt, &yt, [x.parse().unwrap(), y.parse().unwrap()])
            })
            .collect();
        let legend = doc
            .descendants()
            .find(|n| n.attribute("class") == Some("legend") && n.attribute("data-rank") == Some(&rank.to_string()))
            .and_then(|g| g.descendants().find(|n| n.has_tag_name("text")))
            .and_then(|n| n.text())
            .unwrap();
        assert!(legend.starts_with(&format!("#{rank}  max error {:.2e} mm", c.max_error)), "{legend}");
        assert_eq!(legend.contains("not valid"), !c.is_valid(), "{legend}");
        if !c.is_valid() {
            continue;
        }
        // The path is swept through the targets' inputs: it holds the pose at each, which is
        // the candidate's error from the target.
        for (i, t) in targets.iter().enumerate() {
            let near = pts.iter().map(|p| (p[0] - t[0]).hypot(p[1] - t[1])).fold(f64::INFINITY, f64::min);
            assert!(near <= c.errors[i] + tol * 1.5, "candidate {rank}, target {i}: {near} > {} + {tol}", c.errors[i]);
        }
        // The mechanism is drawn at its first target: a joint circle at the traced point there.
        let joints: Vec<[f64; 2]> = doc
            .descendants()
            .filter(|n| {
                n.attribute("class") == Some("candidate") && n.attribute("data-rank") == Some(&rank.to_string())
            })
            .flat_map(|g| g.descendants().filter(|n| n.attribute("class") == Some("joint")))
            .map(|n| {
                world(
                    &xt,
                    &yt,
                    [n.attribute("cx").unwrap().parse().unwrap(), n.attribute("cy").unwrap().parse().unwrap()],
                )
            })
            .collect();
        let t = targets[0];
        assert!(
            joints.iter().any(|q| (q[0] - t[0]).hypot(q[1] - t[1]) <= c.errors[0] + 1.5 * tol),
            "candidate {rank}: a joint at the first target {t:?}: {joints:?}"
        );
    }
    // Mistakes are errors, not panics or NaN.
    let none = candidates(&Coupler::default(), &[], &targets, &config);
    assert!(matches!(none, Err(DrawError::InvalidSetting(_))));
    let nan = candidates(&Coupler::default(), &best, &[[f64::NAN, 0.0]], &config);
    assert!(matches!(nan, Err(DrawError::NonFinite { .. })));
    let wrong = candidates(&Coupler::default(), &best, &targets, &CandidatesConfig::new("q"));
    assert!(matches!(wrong, Err(DrawError::UnknownPoint { .. })));
    let mut short = best[0].clone();
    short.params.pop();
    assert!(matches!(candidates(&Coupler::default(), &[short], &targets, &config), Err(DrawError::InvalidSetting(_))));
    // The best valid candidate's page: the mechanism placed in the targets' plane, the targets
    // marked and numbered at their coordinates (the page's own scale and origin), the traced
    // point at the first target within its error at the first frame, the readouts of p in the
    // targets' plane.
    let valid = best.iter().find(|c| c.is_valid()).unwrap();
    let page = candidate_page(
        &Coupler::default(),
        valid,
        &targets,
        &config,
        &HtmlConfig::new("Best four-bar").show("p.x").show("p.y").with_autoplay(false),
    )
    .unwrap();
    assert!(!page.contains("NaN") && !page.contains("Infinity"));
    std::fs::write(std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("candidate.html"), &page).unwrap();
    let at = page.find("<svg").unwrap();
    let svg = &page[at..at + page[at..].find("</svg>").unwrap() + "</svg>".len()];
    let doc = roxmltree::Document::parse(svg).unwrap();
    let root = doc.root_element();
    let scale: f64 = root.attribute("data-scale").unwrap().parse().unwrap();
    let origin: Vec<f64> = root.attribute("data-origin").unwrap().split(' ').map(|v| v.parse().unwrap()).collect();
    let world = |n: &roxmltree::Node| {
        let (x, y): (f64, f64) =
            (n.attribute("cx").unwrap().parse().unwrap(), n.attribute("cy").unwrap().parse().unwrap());
        [(x - origin[0]) / scale, (origin[1] - y) / scale]
    };
    // Pixels to a tenth: half of it off at most.
    let tol = (0.05 + 1e-6) / scale;
    let marks: Vec<[f64; 2]> =
        doc.descendants().filter(|n| n.attribute("class") == Some("kl-target")).map(|n| world(&n)).collect();
    assert_eq!(marks.len(), targets.len());
    for (q, t) in marks.iter().zip(&targets) {
        assert!((q[0] - t[0]).abs() <= tol && (q[1] - t[1]).abs() <= tol, "{q:?} vs {t:?}");
    }
    let labels: Vec<&str> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("kl-target-label"))
        .filter_map(|n| n.text())
        .collect();
    assert_eq!(labels.first(), Some(&"1"));
    assert_eq!(labels.len(), 10);
    let dot = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("kl-dot") && n.attribute("data-name") == Some("p"))
        .unwrap();
    let q = world(&dot);
    let t = targets[0];
    assert!((q[0] - t[0]).hypot(q[1] - t[1]) <= valid.errors[0] + 2.0 * tol, "p {q:?} at the first target {t:?}");
    // A full turn from the first target: a longer closed path.
    let turn = candidates(&Coupler::default(), &best[..1], &targets, &config.clone().with_span(TAU)).unwrap();
    assert!(roxmltree::Document::parse(&turn).is_ok() && !turn.contains("NaN"));
}

/// The known design itself as a candidate, drawn by a placement of scale `scale` (the whole
/// mechanism, about 4.5 units across at scale 1, made that much smaller) over its own coupler
/// curve's points made as small: the same figure at any scale.
fn scaled_figure(scale: f64) -> (String, Vec<[f64; 2]>) {
    use kinloop::analysis::OptimizerStop;
    use kinloop::synthesis::{Candidate, LocalReport, Origin};
    let truth = Coupler::default();
    let phis: Vec<f64> = (0..6).map(|k| 0.3 + 1.0 * k as f64).collect();
    let states: Vec<_> = phis.iter().map(|&phi| truth.solve(phi).unwrap()).collect();
    let targets: Vec<[f64; 2]> = states.iter().map(|s| [scale * s.out.p.x, scale * s.out.p.y]).collect();
    let c = Candidate {
        start: 0,
        origin: Origin::Seed,
        values: vec![],
        params: vec![1.0, 3.0, 2.5, 3.0, 1.5, 0.6],
        inputs: phis.iter().map(|&phi| vec![phi]).collect(),
        placement: Some([0.0, 0.0, 0.0, scale]),
        positions: states.iter().map(|s| vec![s.q.beta, s.q.gamma]).collect(),
        errors: vec![0.0; phis.len()],
        max_error: 0.0,
        rms_error: 0.0,
        defects: vec![],
        min_transmission: None,
        four_bar: None,
        local: LocalReport { evaluations: 0, iterations: 0, stop: OptimizerStop::Converged, residual: 0.0 },
    };
    let config = CandidatesConfig::new("p").with_length_unit("m");
    (candidates(&Coupler::default(), &[c], &targets, &config).unwrap(), targets)
}

/// Tick labels at metre, millimetre and micrometre scale: short (a few significant digits, the
/// plot module's style: decimals down to 1e-5, a power of ten below), the same digits at every
/// scale, and each at its tick (the targets read back through them at their coordinates).
#[test]
fn tick_labels_are_readable_at_metre_millimetre_and_micrometre_scale() {
    let mut shapes = Vec::new();
    for (scale, power) in [(1.0, ""), (1e-3, ""), (1e-6, "e-6")] {
        let (svg, targets) = scaled_figure(scale);
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let labels = |class: &str| -> Vec<String> {
            doc.descendants()
                .filter(|n| n.attribute("class") == Some(class))
                .map(|n| n.text().unwrap().to_string())
                .collect()
        };
        let (x_labels, y_labels) = (labels("tick-x"), labels("tick-y"));
        for label in x_labels.iter().chain(&y_labels) {
            let (mantissa, exponent) = label.split_once('e').unwrap_or((label, ""));
            let digits = mantissa.trim_start_matches('-').replace('.', "");
            let significant = digits.trim_start_matches('0').trim_end_matches('0');
            assert!(significant.len() <= 3 && label.len() <= 8, "scale {scale}: label {label:?} of {x_labels:?}");
            assert!(!mantissa.contains("0.000") || scale == 1e-3, "scale {scale}: {label:?}");
            // Zero is "0" on an axis of powers of ten, every other label carries the power.
            if !power.is_empty() && label != "0" {
                assert_eq!(format!("e{exponent}"), power, "scale {scale}: {label:?}");
            }
        }
        // The same ticks at every scale: the labels' values over the scale.
        let values = |l: &[String]| l.iter().map(|l| l.parse::<f64>().unwrap() / scale).collect::<Vec<_>>();
        shapes.push((values(&x_labels), values(&y_labels)));
        // Each label at its tick: the targets read back through the labels.
        let (xt, yt) = (ticks(&doc, "tick-x", "x"), ticks(&doc, "tick-y", "y"));
        let sx = (xt[xt.len() - 1].1 - xt[0].1) / (xt[xt.len() - 1].0 - xt[0].0);
        let tol = 0.2 / sx;
        for (i, n) in doc.descendants().filter(|n| n.attribute("class") == Some("target")).enumerate() {
            let at = |k: &str| n.attribute(k).unwrap().parse::<f64>().unwrap();
            let q = world(&xt, &yt, [at("cx"), at("cy")]);
            let t = targets[i];
            assert!(
                (q[0] - t[0]).abs() <= tol && (q[1] - t[1]).abs() <= tol,
                "scale {scale}, target {i}: {q:?} vs {t:?}"
            );
        }
    }
    for (x, y) in &shapes[1..] {
        for (a, b) in x.iter().zip(&shapes[0].0).chain(y.iter().zip(&shapes[0].1)) {
            assert!((a - b).abs() <= 1e-9 * b.abs().max(1.0), "{shapes:?}");
        }
        assert_eq!((x.len(), y.len()), (shapes[0].0.len(), shapes[0].1.len()));
    }
}
