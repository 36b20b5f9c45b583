//! A sweep drawn end to end: a slider-crank's table of states charted against the crank angle
//! with its dead centres marked; the marks sit where the closed-form dead centres fall on the
//! chart's labelled scales.

use kinloop_runtime::Table;
use kinloop_runtime::analysis::Sampled;
use kinloop_viz::plot::{Axis, Kind, Panel, Series, panels_svg};
use std::f64::consts::TAU;

mod figure_check;

/// `(label, pixel position)` of the tick labels of one axis, in document order.
fn ticks(doc: &roxmltree::Document, class: &str, coordinate: &str, offset: f64) -> Vec<(f64, f64)> {
    doc.descendants()
        .filter(|n| n.attribute("class") == Some(class))
        .map(|n| {
            (n.text().unwrap().parse().unwrap(), n.attribute(coordinate).unwrap().parse::<f64>().unwrap() - offset)
        })
        .collect()
}

/// The pixel of value `v` on a scale given by its first two ticks.
fn at(t: &[(f64, f64)], v: f64) -> f64 {
    t[0].1 + (v - t[0].0) / (t[1].0 - t[0].0) * (t[1].1 - t[0].1)
}

kinloop::mechanism! {
    /// Offset slider-crank: crank `r` at the origin, rod `l`, slider C = (x, e) on the crank's
    /// side of the line y = e.
    pub struct SliderCrank {
        params r, l, e;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oabc: r @ phi + l @ psi == (x, e);
    }
}

#[test]
fn dead_centres_are_marked_where_the_closed_form_puts_them() {
    let m = SliderCrank { r: 0.03, l: 0.1, e: 0.012 };
    let turn = Sampled::sweep(&m, 0.0, TAU, 181, [0.0, 0.13]).unwrap();
    let table = Table::from_states::<SliderCrank, 2, 1, 0>(turn.states());
    let range = turn.range(SliderCrank::COL.x).unwrap();
    let metre = Kind::length("m");
    let panel = Panel::new(Axis::length("slider position x", "m"))
        .with(Series::from_table(&table, "phi", "x", metre).unwrap())
        .with_marks([(range.max.x, range.max.value), (range.min.x, range.min.value)]);
    let analog = Panel::new(Axis::new("x'", Kind::LengthAnalog("m".into())))
        .with(Series::from_table(&table, "phi", "d(x)/d(phi)", Kind::LengthAnalog("m".into())).unwrap());
    let svg = panels_svg("Slider-crank", &Axis::angle("crank angle φ"), &[panel, analog]).unwrap();
    kinloop_viz::plot::save(&std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("plot/dead_centres.svg"), &svg)
        .unwrap();
    figure_check::sound(&svg);
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let panel0 = doc.descendants().find(|n| n.attribute("class") == Some("panel")).unwrap();
    let sub = roxmltree::Document::parse(&svg[panel0.range()]).unwrap();
    let (xt, yt) = (ticks(&sub, "tick-label x", "x", 0.0), ticks(&sub, "tick-label y", "y", 4.0));
    let marks: Vec<(f64, f64)> = sub
        .descendants()
        .filter(|n| n.attribute("class") == Some("mark"))
        .map(|n| (n.attribute("cx").unwrap().parse().unwrap(), n.attribute("cy").unwrap().parse().unwrap()))
        .collect();
    // Outer dead centre: crank and rod stretched, x = sqrt((l + r)^2 - e^2) at atan2(e, x);
    // inner: folded, x = sqrt((l - r)^2 - e^2) at pi + atan2(e, x) (the crank and rod triangles).
    let outer = (0.13f64.powi(2) - 0.012f64.powi(2)).sqrt();
    let inner = (0.07f64.powi(2) - 0.012f64.powi(2)).sqrt();
    let expected =
        [(0.012f64.atan2(outer).to_degrees(), outer), ((-0.012f64).atan2(-inner).rem_euclid(TAU).to_degrees(), inner)];
    assert_eq!(marks.len(), 2);
    for ((px, py), (deg, x)) in marks.iter().zip(expected) {
        // 1/100 pixel of written precision on the mark and on each tick label.
        assert!((px - at(&xt, deg)).abs() < 0.02, "{px} vs {}", at(&xt, deg));
        assert!((py - at(&yt, x)).abs() < 0.02, "{py} vs {}", at(&yt, x));
    }
    assert!(svg.contains("x' [m/rad]") && svg.contains("slider position x [m]"));
}
