//! Text as strokes: every `<text>` of an SVG document replaced by a path drawn with the built-in
//! Hershey stroke font ([`super::hershey`]), so a renderer without fonts (resvg here, which
//! loads none) still draws every label, tick and title.
//!
//! Why a stroke font rather than resvg's `text` feature with an embedded outline font: that
//! feature brings a font database and a text shaper (fontdb, rustybuzz, ttf-parser) and still
//! needs font data, either the system's (absent on a bare CI machine, different elsewhere) or
//! a font file shipped in the package (which ships only Rust sources and its licence texts,
//! and an open font's licence would have to travel with it); an outline font with Greek is
//! hundreds of kilobytes, the stroke glyphs here a few. The stroke font needs no dependency
//! beyond the XML reader resvg already uses, and draws the same on every machine. Text keeps its position, size, anchor, rotation, colour and visibility; the
//! face is a plain sans-serif of strokes rather than the viewer's.

use super::hershey::{GREEK_LOWER, GREEK_UPPER, LATIN};
use super::svg::num;
use crate::escape::escape;
use std::fmt::Write;

/// Cap line and baseline of the glyphs, in glyph units (y down).
const CAP_LINE: f64 = -12.0;
const BASELINE: f64 = 9.0;
/// Cap height of a sans-serif face as a fraction of its font size.
const CAP_EM: f64 = 0.7;
/// Stroke width as a fraction of the font size (a regular weight).
const WEIGHT: f64 = 0.085;
/// The SVG default font size (`medium`), in pixels.
const DEFAULT_SIZE: f64 = 16.0;

/// One glyph: its left and right bounds and its strokes (polylines), in glyph units.
struct Glyph {
    left: f64,
    right: f64,
    strokes: Vec<Vec<[f64; 2]>>,
}

/// Decodes a JHF glyph string (see [`super::hershey`]).
fn decode(jhf: &str) -> Glyph {
    let c = |b: u8| b as f64 - b'R' as f64;
    let b = jhf.as_bytes();
    let mut strokes = vec![Vec::new()];
    for pair in b[2..].chunks_exact(2) {
        if pair == b" R" {
            strokes.push(Vec::new());
        } else if let Some(s) = strokes.last_mut() {
            s.push([c(pair[0]), c(pair[1])]);
        }
    }
    strokes.retain(|s| !s.is_empty());
    Glyph { left: c(b[0]), right: c(b[1]), strokes }
}

/// The glyph of an ASCII character (printable; anything else is the box).
fn ascii(ch: char) -> Glyph {
    match (ch as usize).checked_sub(32).and_then(|i| LATIN.get(i)) {
        Some(g) => decode(g),
        None => tofu(),
    }
}

/// An empty box: a character the font does not hold, shown as missing rather than dropped.
fn tofu() -> Glyph {
    let (l, r, t, b) = (-5.0, 5.0, CAP_LINE, BASELINE);
    Glyph { left: -8.0, right: 8.0, strokes: vec![vec![[l, t], [r, t], [r, b], [l, b], [l, t]]] }
}

/// A circle of radius `r` about `c`, as a polyline.
fn circle(c: [f64; 2], r: f64) -> Vec<[f64; 2]> {
    (0..=16)
        .map(|k| (k as f64 * std::f64::consts::TAU / 16.0).sin_cos())
        .map(|(s, co)| [c[0] + r * co, c[1] + r * s])
        .collect()
}

/// `g` scaled by `k` about the baseline's origin and raised by `up` (superscripts).
fn scaled(g: Glyph, k: f64, up: f64) -> Glyph {
    let map = |[x, y]: [f64; 2]| [x * k, BASELINE + (y - BASELINE) * k - up];
    Glyph {
        left: g.left * k,
        right: g.right * k,
        strokes: g.strokes.into_iter().map(|s| s.into_iter().map(map).collect()).collect(),
    }
}

/// The glyph of `ch`.
fn glyph(ch: char) -> Glyph {
    let greek = |table: &[&str; 24], first: u32, ch: char| {
        // The code points skip one (U+03A2 unassigned; U+03C2, final sigma, drawn as sigma).
        let k = ch as u32 - first;
        let k = if k > 17 {
            k - 1
        } else if k == 17 && first == 0x3B1 {
            17
        } else {
            k
        };
        table.get(k as usize).map_or_else(tofu, |g| decode(g))
    };
    match ch {
        // The Hershey space is half an em wide; a sans-serif's is about a third of that less.
        ' ' => Glyph { left: -5.0, right: 5.0, strokes: Vec::new() },
        '!'..='~' => ascii(ch),
        '\u{391}'..='\u{3A9}' if ch != '\u{3A2}' => greek(&GREEK_UPPER, 0x391, ch),
        '\u{3B1}'..='\u{3C9}' => greek(&GREEK_LOWER, 0x3B1, ch),
        'µ' => glyph('μ'),
        '°' => Glyph { left: -4.0, right: 4.0, strokes: vec![circle([0.0, CAP_LINE + 3.0], 3.0)] },
        '¹' => scaled(ascii('1'), 0.6, 10.0),
        '²' => scaled(ascii('2'), 0.6, 10.0),
        '³' => scaled(ascii('3'), 0.6, 10.0),
        '·' | '⋅' => Glyph { left: -4.0, right: 4.0, strokes: vec![circle([0.0, -1.5], 1.0)] },
        '…' => {
            let dot = |x: f64| circle([x, BASELINE - 1.0], 1.0);
            Glyph { left: -9.0, right: 9.0, strokes: vec![dot(-5.0), dot(0.0), dot(5.0)] }
        }
        '−' | '–' | '—' => ascii('-'),
        '×' => ascii('x'),
        '′' | '’' => ascii('\''),
        _ => tofu(),
    }
}

/// The strokes of `text` set at font size `size` with its baseline through `(x, y)` and the
/// given anchor, as SVG path data (empty for blank text).
pub(crate) fn path_data(text: &str, x: f64, y: f64, size: f64, anchor: &str) -> String {
    let scale = CAP_EM * size / (BASELINE - CAP_LINE);
    let glyphs: Vec<Glyph> = text.chars().map(glyph).collect();
    let width: f64 = glyphs.iter().map(|g| g.right - g.left).sum::<f64>() * scale;
    let mut pen = x - match anchor {
        "middle" => 0.5 * width,
        "end" => width,
        _ => 0.0,
    };
    let mut d = String::new();
    for g in &glyphs {
        for s in &g.strokes {
            for (i, [gx, gy]) in s.iter().enumerate() {
                let (px, py) = (pen + (gx - g.left) * scale, y + (gy - BASELINE) * scale);
                let _ = write!(d, "{}{},{}", if i == 0 { 'M' } else { 'L' }, num(px), num(py));
            }
            // A single point (a dot) is drawn as a round-capped zero-length stroke.
            if s.len() == 1 {
                d.push_str("h0");
            }
        }
        pen += (g.right - g.left) * scale;
    }
    d
}

/// A presentation attribute of `node`, or of its nearest ancestor that has it.
fn inherited<'a>(node: roxmltree::Node<'a, 'a>, name: &str) -> Option<&'a str> {
    node.ancestors().find_map(|n| n.attribute(name))
}

/// The first number of a length attribute (`"12"`, `"12px"`, `"3 4 5"`).
fn number(s: &str) -> Option<f64> {
    let first = s.split([' ', ',']).find(|t| !t.is_empty())?;
    first.trim_end_matches("px").parse().ok().filter(|v: &f64| v.is_finite())
}

/// `svg` with each `<text>` element replaced by the path of its strokes (same place, size,
/// anchor, colour, rotation, class and visibility). Errors: the document is not XML.
pub(crate) fn outline(svg: &str) -> Result<String, String> {
    let doc = roxmltree::Document::parse(svg).map_err(|e| e.to_string())?;
    let mut out = String::with_capacity(svg.len());
    let mut done = 0;
    for node in doc.descendants().filter(|n| n.is_element() && n.tag_name().name() == "text") {
        let range = node.range();
        if range.start < done {
            continue;
        }
        out.push_str(&svg[done..range.start]);
        done = range.end;
        let text: String = node.descendants().filter(|n| n.is_text()).filter_map(|n| n.text()).collect();
        let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
        let fill = inherited(node, "fill").unwrap_or("black");
        if text.is_empty() || fill == "none" {
            continue;
        }
        let size = inherited(node, "font-size").and_then(number).unwrap_or(DEFAULT_SIZE);
        let (x, y) =
            (node.attribute("x").and_then(number).unwrap_or(0.0), node.attribute("y").and_then(number).unwrap_or(0.0));
        let anchor = inherited(node, "text-anchor").unwrap_or("start");
        let d = path_data(&text, x, y, size, anchor);
        // A text's own outline (a halo behind it: `stroke` with `paint-order="stroke"`) is a
        // wider stroke of the same path, drawn first.
        let halo = node.attribute("stroke").filter(|c| *c != "none");
        let halo_width = node.attribute("stroke-width").and_then(number).unwrap_or(1.0);
        let strokes = halo.map(|c| (c, WEIGHT * size + halo_width)).into_iter().chain([(fill, WEIGHT * size)]);
        for (colour, width) in strokes {
            let _ = write!(
                out,
                r#"<path d="{d}" fill="none" stroke="{}" stroke-width="{}" stroke-linecap="round" stroke-linejoin="round""#,
                escape(colour),
                num(width)
            );
            for name in ["class", "transform", "visibility", "opacity", "fill-opacity"] {
                if let Some(v) = node.attribute(name) {
                    let v = if name == "fill-opacity" { ("stroke-opacity", v) } else { (name, v) };
                    let _ = write!(out, r#" {}="{}""#, v.0, escape(v.1));
                }
            }
            out.push_str("/>");
        }
    }
    out.push_str(&svg[done..]);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_printable_character_and_the_greek_letters_have_strokes() {
        for ch in ('!'..='~').chain('α'..='ω').chain('Α'..='Ω').filter(|c| *c != '\u{3A2}') {
            let g = glyph(ch);
            assert!(!g.strokes.is_empty() && g.right > g.left, "{ch}");
        }
        // The letters are where the code points say: φ is not ψ.
        let phi = decode(GREEK_LOWER[20]);
        assert_eq!(glyph('φ').strokes, phi.strokes);
        assert_eq!(glyph('ς').strokes, glyph('σ').strokes);
        assert_eq!(glyph('Ω').strokes, decode(GREEK_UPPER[23]).strokes);
        // A character the font lacks is a box, not nothing.
        assert_eq!(glyph('€').strokes.len(), 1);
    }

    #[test]
    fn anchors_place_the_text_and_its_height_is_the_cap_height() {
        let d = path_data("H", 100.0, 50.0, 20.0, "start");
        let ys: Vec<f64> = d
            .split(['M', 'L'])
            .filter(|s| !s.is_empty())
            .map(|p| p.split(',').nth(1).unwrap().trim_end_matches("h0").parse().unwrap())
            .collect();
        let (top, bottom) = ys.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| (a.min(*y), b.max(*y)));
        assert!((bottom - 50.0).abs() < 0.01 && (bottom - top - CAP_EM * 20.0).abs() < 0.01, "{top} {bottom}");
        let xs =
            |a: &str| -> f64 { path_data("H", 100.0, 50.0, 20.0, a)[1..].split(',').next().unwrap().parse().unwrap() };
        let (start, middle, end) = (xs("start"), xs("middle"), xs("end"));
        // Half the width each step, to the 0.1 px the coordinates are written with.
        assert!(start > middle && middle > end && ((start - middle) - (middle - end)).abs() <= 0.2 + 1e-9);
    }

    #[test]
    fn texts_become_paths_and_the_rest_stays() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="10" height="10" font-size="12"><g fill="red"><text x="1" y="2" transform="rotate(-90 1 2)">φ &amp; x</text></g><circle r="1"/></svg>"#;
        let out = outline(svg).unwrap();
        assert!(!out.contains("<text") && out.contains(r#"stroke="red""#) && out.contains("rotate(-90 1 2)"), "{out}");
        assert!(out.ends_with(r#"<circle r="1"/></svg>"#));
        // A halo: the wider white stroke first, then the text's own.
        let halo = r#"<svg xmlns="http://www.w3.org/2000/svg"><text font-size="10" stroke="white" stroke-width="3" paint-order="stroke">b</text></svg>"#;
        let out = outline(halo).unwrap();
        let (white, ink) =
            (out.find(r#"stroke="white" stroke-width="3.9""#), out.find(r#"stroke="black" stroke-width="0.9""#));
        assert!(white.is_some() && ink.is_some() && white < ink, "{out}");
        assert!(outline("<svg").is_err());
    }
}
