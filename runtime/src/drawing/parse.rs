//! Reading the text `mechanism!` emits (one string constant keeps the generated code short):
//!
//! ```text
//! kinloop-drawing 1
//! t <entry> <entry> ...                 the tape: c:1.5 p:0 x:0 q:1 add:a,b sub:a,b mul:a,b
//!                                       div:a,b neg:a powi:a,n powf:a,b atan2:y,x sin:a floor:a ...
//!                                       select:a,b,x,y (x if a <= b, y if b < a, else NaN)
//! j <name> <g|m> <n|-> <x> <y>          a joint: fixed or moving, named or not, tape entries
//! s <from> <to> <kind> <angle|-> <term> a segment: link, ground, slider-fixed,
//!                                       slider-turning or construction
//! p <name|-> <joint> <joint> ...        a plate
//! g <plate> <segment>                   a slider's turning guide, part of a plate
//! n <text>                              a note
//! ```
//!
//! Every index is checked: a tape entry reads earlier entries only, joints and segments read
//! existing entries and joints. A text that does not read is an error, never a panic.

use super::tape::{Func, TapeOp};
use super::{Description, FORMAT, Joint, Plate, Segment, SegmentKind};
use crate::error::Error;

impl Description {
    /// Reads a description in the macro's text format.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the line that does not read.
    pub fn parse(text: &str) -> Result<Description, Error> {
        let mut lines = text.lines();
        if lines.next() != Some(FORMAT) {
            return Err(bad(1, &format!("the first line must be `{FORMAT}`")));
        }
        let mut d = Description {
            joints: Vec::new(),
            segments: Vec::new(),
            plates: Vec::new(),
            notes: Vec::new(),
            tape: Vec::new(),
        };
        for (i, line) in lines.enumerate() {
            let n = i + 2;
            let (tag, rest) = line.split_once(' ').unwrap_or((line, ""));
            match tag {
                "t" => {
                    for entry in rest.split_whitespace() {
                        let op =
                            tape_entry(entry, d.tape.len()).ok_or_else(|| bad(n, &format!("tape entry `{entry}`")))?;
                        d.tape.push(op);
                    }
                }
                "j" => d.joints.push(joint(rest, d.tape.len()).ok_or_else(|| bad(n, "a joint"))?),
                "s" => d.segments.push(segment(rest, d.tape.len(), d.joints.len()).ok_or_else(|| bad(n, "a segment"))?),
                "p" => d.plates.push(plate(rest, d.joints.len()).ok_or_else(|| bad(n, "a plate"))?),
                "g" => {
                    let (p, s) = guide(rest, &d).ok_or_else(|| bad(n, "a guide"))?;
                    d.plates[p].guides.push(s);
                }
                "n" => d.notes.push(rest.to_string()),
                _ => return Err(bad(n, &format!("unknown line `{tag}`"))),
            }
        }
        Ok(d)
    }
}

fn bad(line: usize, what: &str) -> Error {
    Error::InvalidArgument(format!("the drawing description does not read at line {line}: {what}"))
}

/// An index below `len`.
fn index(s: &str, len: usize) -> Option<usize> {
    s.parse::<usize>().ok().filter(|&i| i < len)
}

fn tape_entry(entry: &str, len: usize) -> Option<TapeOp> {
    let (op, args) = entry.split_once(':')?;
    let one = || index(args, len);
    let two = || {
        let (a, b) = args.split_once(',')?;
        Some((index(a, len)?, index(b, len)?))
    };
    let leaf = || args.parse::<usize>().ok();
    Some(match op {
        "c" => TapeOp::Const(args.parse().ok()?),
        "p" => TapeOp::Param(leaf()?),
        "x" => TapeOp::Input(leaf()?),
        "q" => TapeOp::Unknown(leaf()?),
        "add" => two().map(|(a, b)| TapeOp::Add(a, b))?,
        "sub" => two().map(|(a, b)| TapeOp::Sub(a, b))?,
        "mul" => two().map(|(a, b)| TapeOp::Mul(a, b))?,
        "div" => two().map(|(a, b)| TapeOp::Div(a, b))?,
        "powf" => two().map(|(a, b)| TapeOp::Powf(a, b))?,
        "atan2" => two().map(|(a, b)| TapeOp::Atan2(a, b))?,
        "neg" => TapeOp::Neg(one()?),
        "select" => {
            let v: Vec<usize> = args.split(',').map(|a| index(a, len)).collect::<Option<_>>()?;
            let [a, b, x, y] = v[..] else { return None };
            TapeOp::Select(a, b, x, y)
        }
        "powi" => {
            let (a, n) = args.split_once(',')?;
            TapeOp::Powi(index(a, len)?, n.parse().ok()?)
        }
        f => TapeOp::Func(Func::ALL.iter().find(|(name, _)| *name == f)?.1, one()?),
    })
}

fn joint(rest: &str, tape: usize) -> Option<Joint> {
    let f: Vec<&str> = rest.split(' ').collect();
    let [name, kind, named, x, y] = f[..] else { return None };
    let ground = match kind {
        "g" => true,
        "m" => false,
        _ => return None,
    };
    Some(Joint { name: name.to_string(), ground, named: named == "n", x: index(x, tape)?, y: index(y, tape)? })
}

fn segment(rest: &str, tape: usize, joints: usize) -> Option<Segment> {
    let mut f = rest.splitn(5, ' ');
    let (from, to) = (index(f.next()?, joints)?, index(f.next()?, joints)?);
    let kind = match f.next()? {
        "link" => SegmentKind::Link,
        "ground" => SegmentKind::Ground,
        "slider-fixed" => SegmentKind::Slider { fixed_guide: true },
        "slider-turning" => SegmentKind::Slider { fixed_guide: false },
        "construction" => SegmentKind::Construction,
        _ => return None,
    };
    let angle = match f.next()? {
        "-" => None,
        a => Some(index(a, tape)?),
    };
    Some(Segment { from, to, kind, angle, term: f.next()?.to_string() })
}

fn plate(rest: &str, joints: usize) -> Option<Plate> {
    let mut f = rest.split(' ');
    let name = match f.next()? {
        "-" => None,
        n => Some(n.to_string()),
    };
    let joints = f.map(|j| index(j, joints)).collect::<Option<Vec<_>>>()?;
    (joints.len() >= 2).then_some(Plate { name, joints, guides: Vec::new() })
}

/// A plate and a slider on a turning guide that starts at one of the plate's joints.
fn guide(rest: &str, d: &Description) -> Option<(usize, usize)> {
    let (p, s) = rest.split_once(' ')?;
    let (p, s) = (index(p, d.plates.len())?, index(s, d.segments.len())?);
    let seg = &d.segments[s];
    (seg.kind == SegmentKind::Slider { fixed_guide: false } && d.plates[p].joints.contains(&seg.from)).then_some((p, s))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SLIDER_CRANK: &str = "kinloop-drawing 1
t c:0 p:0 x:0 cos:2 mul:1,3 sin:2 mul:1,5 q:1 p:1
j origin g - 0 0
j a.l1 m - 4 6
s 0 1 link 2 a: r @ phi
s 0 1 slider-fixed - a: (x, e)
p - 0 1
n a note, with spaces";

    #[test]
    fn a_description_reads_and_evaluates() {
        let d = Description::parse(SLIDER_CRANK).unwrap();
        assert_eq!(d.joints.len(), 2);
        assert_eq!(d.segments[0].term, "a: r @ phi");
        assert_eq!(d.segments[1].kind, SegmentKind::Slider { fixed_guide: true });
        assert_eq!(d.notes, ["a note, with spaces"]);
        let v = d.evaluate(&[2.0, 0.5], &[0.3], &[0.0, 1.0]).unwrap();
        assert_eq!(v.joints, [[0.0, 0.0], [2.0 * 0.3f64.cos(), 2.0 * 0.3f64.sin()]]);
        assert_eq!(v.angles, [Some(0.3), None]);
    }

    /// `floor:a` (the declaration's `floor`, and `wrap(x, p)` = `x - p floor(x / p)`): the
    /// largest integer not above, negative arguments and NaN included.
    #[test]
    fn floor_reads_and_evaluates() {
        let text = "kinloop-drawing 1
t x:0 floor:0 c:6.283185307179586 div:0,2 floor:3 mul:2,4 sub:0,5
j f m - 1 6";
        let d = Description::parse(text).unwrap();
        let p = std::f64::consts::TAU;
        for x in [-7.5, -1e-300, 0.0, 2.0, p, 20.0] {
            let v = d.evaluate(&[], &[x], &[]).unwrap();
            let want = [x.floor(), x - p * (x / p).floor()];
            assert_eq!(v.joints, [want], "at {x}");
            assert!((0.0..=p).contains(&v.joints[0][1]), "at {x}");
        }
        assert_eq!(d.evaluate(&[], &[-0.5], &[]).unwrap().joints[0][0], -1.0);
        let nan = d.evaluate(&[], &[f64::NAN], &[]).unwrap();
        assert!(nan.joints[0].iter().all(|v| v.is_nan()));
        let inf = d.evaluate(&[], &[f64::NEG_INFINITY], &[]).unwrap();
        assert_eq!(inf.joints[0][0], f64::NEG_INFINITY);
    }

    /// A `g` line puts a turning guide into a plate, which the words then name.
    #[test]
    fn a_guide_line_puts_a_turning_guide_into_a_plate() {
        let text = "kinloop-drawing 1
t c:0 c:1 q:0
j o g - 0 0
j b m - 1 0
j tip m - 0 1
s 0 1 slider-turning 2 slot: s @ theta
p - 0 2
g 0 0";
        let d = Description::parse(text).unwrap();
        assert_eq!(d.plates[0].guides, [0]);
        assert!(d.to_string().contains("plate -: o, tip; the guide of slot: s @ theta\n"), "{d}");
    }

    #[test]
    fn a_broken_description_is_an_error_not_a_panic() {
        for broken in [
            "",
            "kinloop-drawing 2",
            "kinloop-drawing 1\nt add:0,1",
            "kinloop-drawing 1\nt c:1 add:0,1",
            "kinloop-drawing 1\nt c:x",
            "kinloop-drawing 1\nt c:1\nj a g - 0 1",
            "kinloop-drawing 1\nt c:1\nj a g - 0 0\ns 0 1 link - t",
            "kinloop-drawing 1\nt c:1\nj a g - 0 0\ns 0 0 bar - t",
            "kinloop-drawing 1\nt c:1\nj a g - 0 0\np - 0",
            "kinloop-drawing 1\nt c:1\nj a g - 0 0\nj b g - 0 0\ns 0 1 slider-turning 0 t\ng 0 0",
            "kinloop-drawing 1\nt c:1\nj a g - 0 0\nj b g - 0 0\ns 0 1 slider-fixed 0 t\np - 0 1\ng 0 0",
            "kinloop-drawing 1\nt c:1\nj a g - 0 0\nj b g - 0 0\nj c g - 0 0\ns 1 0 slider-turning 0 t\np - 0 2\ng 0 0",
            "kinloop-drawing 1\nz",
            "kinloop-drawing 1\nt frob:0",
            "kinloop-drawing 1\nt c:1 floor:1",
            "kinloop-drawing 1\nt c:1 floor:0,0",
        ] {
            assert!(matches!(Description::parse(broken), Err(Error::InvalidArgument(_))), "{broken:?}");
        }
        // Leaves beyond the slices given are an error at evaluation.
        let d = Description::parse(SLIDER_CRANK).unwrap();
        assert!(matches!(d.evaluate(&[2.0], &[0.3], &[0.0, 1.0]), Err(Error::InvalidArgument(_))));
    }
}
