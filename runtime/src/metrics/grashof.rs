//! Grashof classification of a four-bar loop: which links can turn fully.
//!
//! With `s` the shortest, `l` the longest and `p`, `q` the other two links, a four-bar is a
//! Grashof linkage when `s + l < p + q`: the shortest link turns fully relative to every other.
//! A link turns fully relative to the ground when it or the ground is the shortest. When
//! `s + l = p + q` (a change-point linkage) the links can line up flat, where the assembly mode
//! can change; when `s + l > p + q` no link turns fully (a non-Grashof triple rocker).

use crate::error::Error;
use std::fmt;

/// The four links of a four-bar loop (lengths in any one unit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBarLinks {
    /// The fixed link between the two ground pivots.
    pub ground: f64,
    /// The driven (input) link, pivoted to the ground.
    pub input: f64,
    /// The coupler joining input and output.
    pub coupler: f64,
    /// The output (follower) link, pivoted to the ground.
    pub output: f64,
}

/// One link of a four-bar.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Link {
    /// The frame, between the two fixed pivots.
    Ground,
    /// The driven crank.
    Input,
    /// The link joining input and output.
    Coupler,
    /// The follower (rocker or crank).
    Output,
}

/// The Grashof class of a four-bar, named from the input's point of view.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum GrashofClass {
    /// Grashof; the input turns fully, the output rocks.
    CrankRocker,
    /// Grashof; the output turns fully, the input rocks.
    RockerCrank,
    /// Grashof with the ground the shortest link (drag link): input and output turn fully.
    DoubleCrank,
    /// Grashof with the coupler the shortest link: input and output rock, the coupler turns fully.
    DoubleRocker,
    /// `s + l = p + q`: the links can line up flat, where the assembly mode can change.
    ChangePoint,
    /// Non-Grashof, `s + l > p + q`: no link turns fully.
    TripleRocker,
}

impl fmt::Display for GrashofClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            GrashofClass::CrankRocker => "crank-rocker",
            GrashofClass::RockerCrank => "rocker-crank",
            GrashofClass::DoubleCrank => "double-crank",
            GrashofClass::DoubleRocker => "Grashof double-rocker",
            GrashofClass::ChangePoint => "change point",
            GrashofClass::TripleRocker => "non-Grashof triple-rocker",
        })
    }
}

/// The classification of a four-bar: its class and which links turn fully relative to the ground.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grashof {
    /// Grashof, non-Grashof or change point.
    pub class: GrashofClass,
    /// The shortest link (the first of ground, input, coupler, output on a tie; lengths equal to
    /// within rounding tie, as for the class).
    pub shortest: Link,
    /// `(s + l) - (p + q)` divided by the sum of the four lengths: negative for Grashof
    /// linkages, zero at a change point, positive for triple rockers (a scale-free margin).
    /// A sweep takes a linkage within a few `1e-14` of a change point (at the default
    /// `SweepConfig::singular_pivot`) for one: see
    /// [`EventKind::SingularCrossing`](crate::EventKind::SingularCrossing).
    pub margin: f64,
    /// The input turns fully relative to the ground (in a change point: through the flat position).
    pub input_turns: bool,
    /// The output turns fully relative to the ground.
    pub output_turns: bool,
    /// The coupler turns fully relative to the ground.
    pub coupler_turns: bool,
}

/// Classifies a four-bar loop.
///
/// Lengths equal to within a few units of rounding (relative to their sum) count as equal,
/// so a parallelogram declared in any unit is a change point. Errors (`InvalidArgument`): a
/// length that is not finite and positive, one longer than the other three together (the loop
/// cannot close), or one as long as the other three together (it closes only lying flat, every
/// link on one line, and cannot move).
///
/// ```
/// use kinloop_runtime::metrics::{FourBarLinks, GrashofClass, grashof};
/// let g = grashof(FourBarLinks { ground: 4.0, input: 1.0, coupler: 3.5, output: 3.0 })?;
/// assert_eq!(g.class, GrashofClass::CrankRocker);
/// assert!(g.input_turns && !g.output_turns);
/// let g = grashof(FourBarLinks { ground: 4.0, input: 3.0, coupler: 2.0, output: 2.5 })?;
/// assert_eq!(g.class, GrashofClass::TripleRocker);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn grashof(links: FourBarLinks) -> Result<Grashof, Error> {
    let FourBarLinks { ground: d, input: a, coupler: b, output: c } = links;
    let lengths = [d, a, b, c];
    if let Some(bad) = lengths.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        return Err(Error::InvalidArgument(format!("four-bar link lengths must be finite and positive, got {bad}")));
    }
    // Lengths near the largest f64 sum to infinity (and `inf - inf` made the margin NaN and the
    // class a change point): they are classified scaled down by a power of two, which is exact
    // and changes neither the class nor the margin.
    let (given, scale) = (lengths, if lengths.iter().sum::<f64>().is_finite() { 1.0 } else { 0.125 });
    let lengths = lengths.map(|v| v * scale);
    let [d, a, b, c] = lengths;
    let sum: f64 = lengths.iter().sum();
    let tol = 8.0 * f64::EPSILON * sum;
    let longest = lengths.iter().copied().fold(0.0, f64::max);
    let rest = sum - longest;
    if longest > rest + tol {
        return Err(Error::InvalidArgument(format!(
            "a four-bar with links {given:?} cannot close: the longest is longer than the other three together"
        )));
    }
    // Equal to within the rounding of the sums (and of lengths declared in decimal, as
    // `0.1 + 0.2 + 0.3` against `0.6`), the same tolerance that judges a change point: no
    // triple rocker, which moves, but a straight line that cannot.
    if longest >= rest - tol {
        return Err(Error::InvalidArgument(format!(
            "a four-bar with links {given:?} cannot move: the longest is as long as the other three together, \
             so the loop closes only lying flat, every link on one line"
        )));
    }
    let short = lengths.iter().copied().fold(f64::MAX, f64::min);
    // The first link within rounding of the shortest, as every comparison here takes lengths
    // equal: the first strictly shortest named a link one rounding shorter than the first of a
    // tie (the coupler `0.3 - 0.2` of a kite, where in millimetres the input 100 is named).
    let k_short = lengths.iter().position(|&v| v <= short + tol).unwrap_or(0);
    let shortest = [Link::Ground, Link::Input, Link::Coupler, Link::Output][k_short];
    let excess = short + longest - (sum - short - longest);
    // A link pivoted to the ground turns fully when the opposite dyad closes at both ends of
    // its turn (the diagonal to the other ground pivot is shortest and longest there).
    let le = |x: f64, y: f64| x <= y + tol;
    let input_turns = le((b - c).abs(), (d - a).abs()) && le(d + a, b + c);
    let output_turns = le((a - b).abs(), (d - c).abs()) && le(d + c, a + b);
    let grashof_or_equal = excess <= tol;
    // The coupler turns relative to the ground when either is a shortest link: on a tie (only at
    // a change point) not only the first of them, which `shortest` names (the kite of input and
    // coupler 1, ground and output 3, whose shortest is the input, folds with its coupler
    // turning about the ground pivot).
    let coupler_turns = grashof_or_equal && (b <= short + tol || d <= short + tol);
    let class = if excess.abs() <= tol {
        GrashofClass::ChangePoint
    } else if excess > 0.0 {
        GrashofClass::TripleRocker
    } else {
        match (input_turns, output_turns) {
            (true, true) => GrashofClass::DoubleCrank,
            (true, false) => GrashofClass::CrankRocker,
            (false, true) => GrashofClass::RockerCrank,
            (false, false) => GrashofClass::DoubleRocker,
        }
    };
    Ok(Grashof { class, shortest, margin: excess / sum, input_turns, output_turns, coupler_turns })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;
    use std::f64::consts::{PI, TAU};

    /// Brute force, independent of the Grashof inequalities: the input turns fully when the
    /// loop closes at every input angle of a fine grid (the dyad coupler-output spans the
    /// distance from the input's tip to the output's pivot); likewise for the output.
    fn turns_by_brute_force(pivot_link: f64, far: f64, near: f64, ground: f64) -> bool {
        (0..3600).all(|i| {
            let t = TAU * i as f64 / 3600.0;
            let e = (ground - pivot_link * t.cos()).hypot(pivot_link * t.sin());
            e >= (far - near).abs() && e <= far + near
        })
    }

    #[test]
    fn classes_of_random_four_bars_match_brute_force_turning() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let mut seen = std::collections::HashSet::new();
        for _ in 0..3000 {
            let scale = 10f64.powf(rng.uniform(-6.0, 3.0));
            let l = FourBarLinks {
                ground: rng.uniform(0.1, 4.0) * scale,
                input: rng.uniform(0.1, 4.0) * scale,
                coupler: rng.uniform(0.1, 4.0) * scale,
                output: rng.uniform(0.1, 4.0) * scale,
            };
            let Ok(g) = grashof(l) else { continue };
            // Skip designs within 1 % of a class boundary, where a 0.1 degree grid cannot decide.
            if g.margin.abs() < 0.01 {
                continue;
            }
            let input = turns_by_brute_force(l.input, l.coupler, l.output, l.ground);
            let output = turns_by_brute_force(l.output, l.coupler, l.input, l.ground);
            assert_eq!((g.input_turns, g.output_turns), (input, output), "{l:?}: {g:?}");
            let expected = match (g.margin > 0.0, input, output) {
                (true, _, _) => GrashofClass::TripleRocker,
                (false, true, true) => GrashofClass::DoubleCrank,
                (false, true, false) => GrashofClass::CrankRocker,
                (false, false, true) => GrashofClass::RockerCrank,
                (false, false, false) => GrashofClass::DoubleRocker,
            };
            assert_eq!(g.class, expected, "{l:?}");
            if g.class == GrashofClass::TripleRocker {
                assert!(!input && !output && !g.coupler_turns);
            }
            seen.insert(g.class.to_string());
        }
        assert_eq!(seen.len(), 5, "every non-degenerate class drawn: {seen:?}");
    }

    #[test]
    fn a_parallelogram_is_a_change_point_in_any_unit() {
        for scale in [1e-6, 1e-3, 1.0, 1e3] {
            let g = grashof(FourBarLinks {
                ground: 0.3 * scale,
                input: 0.1 * scale,
                coupler: 0.3 * scale,
                output: 0.1 * scale,
            })
            .unwrap();
            assert_eq!(g.class, GrashofClass::ChangePoint);
            assert!(g.input_turns && g.output_turns, "{g:?}");
        }
    }

    /// Lengths near the largest f64, whose sum overflows, are classified as the same linkage in
    /// any unit: a crank-rocker, with its margin, not a change point of NaN margin.
    #[test]
    fn lengths_near_the_largest_f64_are_classified() {
        let links =
            |k: f64| FourBarLinks { ground: 1e308 * k, input: 0.5e308 * k, coupler: 1e308 * k, output: 1e308 * k };
        let g = grashof(links(1.0)).unwrap();
        let small = grashof(links(2f64.powi(-800))).unwrap();
        assert_eq!(g.class, GrashofClass::CrankRocker, "{g:?}");
        assert_eq!(g, small);
        assert!((g.margin + 0.5 / 3.5).abs() < 1e-15, "{g:?}");
        let err = grashof(FourBarLinks { ground: f64::MAX, input: 1e300, coupler: 1e300, output: 1e300 }).unwrap_err();
        assert!(err.to_string().contains("1.7976931348623157e308"), "{err}");
    }

    /// One link as long as the other three together: the loop closes only lying flat, every
    /// link on one line, and cannot move at all. That is an error saying so (it was classified
    /// a triple rocker, a linkage that moves), in any unit: the lengths `0.1 + 0.2 + 0.3` sum to
    /// one unit in the last place above `0.6`, which the rounding tolerance takes as equal.
    /// A link one part in a billion shorter is a triple rocker again, one longer cannot close.
    #[test]
    fn a_link_as_long_as_the_other_three_cannot_move() {
        for scale in [1e-300, 1e-6, 1e-3, 1.0, 1e3, 1e300, 2f64.powi(1021)] {
            let links = |long: f64| FourBarLinks {
                ground: long * scale,
                input: 0.1 * scale,
                coupler: 0.2 * scale,
                output: 0.3 * scale,
            };
            let err = grashof(links(0.6)).unwrap_err();
            assert!(matches!(&err, Error::InvalidArgument(m) if m.contains("cannot move")), "{scale:e}: {err}");
            let exact = FourBarLinks {
                ground: 0.25 * scale,
                input: 0.5 * scale,
                coupler: 0.125 * scale,
                output: 0.125 * scale,
            };
            let err = grashof(exact).unwrap_err();
            assert!(err.to_string().contains("cannot move"), "{scale:e}: {err}");
            let g = grashof(links(0.6 * (1.0 - 1e-9))).unwrap();
            assert_eq!(g.class, GrashofClass::TripleRocker, "{scale:e}: {g:?}");
            let err = grashof(links(0.6 * (1.0 + 1e-9))).unwrap_err();
            assert!(err.to_string().contains("cannot close"), "{scale:e}: {err}");
        }
    }

    /// A kite whose input and coupler are both the shortest (1, ground and output 3): a change
    /// point whose coupler turns fully about the ground, folded onto the input's pivot (turning
    /// with the input, half a turn from it) or opened (its mirror image in the line from the
    /// input's tip to the output's pivot, turning the other way). The shortest is named the
    /// input (the first on a tie), and the coupler was said not to turn.
    #[test]
    fn a_coupler_tied_for_the_shortest_link_turns() {
        for scale in [1e-6, 1.0, 1e3] {
            let g = grashof(FourBarLinks { ground: 3.0 * scale, input: scale, coupler: scale, output: 3.0 * scale })
                .unwrap();
            assert_eq!((g.class, g.shortest), (GrashofClass::ChangePoint, Link::Input), "{g:?}");
            assert!(g.input_turns && g.coupler_turns && !g.output_turns, "{g:?}");
        }
        // The coupler's angle on the opened kite, by construction: C the mirror image of the
        // input's pivot A = (0, 0) in the line from B (the input's tip) to D = (3, 0). Over one
        // turn of the input it turns once the other way.
        let (mut turned, mut last) = (0.0, None::<f64>);
        for i in 0..=3600 {
            let phi = 1e-3 + TAU * f64::from(i) / 3600.0;
            let (bx, by) = (phi.cos(), phi.sin());
            let (ux, uy) = ((3.0 - bx) / (3.0 - bx).hypot(by), -by / (3.0 - bx).hypot(by));
            // A - B mirrored in the line through B along u.
            let (vx, vy) = (-bx, -by);
            let along = vx * ux + vy * uy;
            let beta = (2.0 * along * uy - vy).atan2(2.0 * along * ux - vx);
            if let Some(prev) = last {
                turned += (beta - prev + PI).rem_euclid(TAU) - PI;
            }
            last = Some(beta);
        }
        assert!((turned + TAU).abs() < 1e-9, "{turned}");
        // Tied with the ground or the output, the coupler turned already (the ground or the
        // coupler named the shortest); tied with neither, a parallelogram's does not.
        let kite = grashof(FourBarLinks { ground: 3.0, input: 3.0, coupler: 1.0, output: 1.0 }).unwrap();
        assert!(kite.coupler_turns, "{kite:?}");
        let parallelogram = grashof(FourBarLinks { ground: 3.0, input: 1.0, coupler: 3.0, output: 1.0 }).unwrap();
        assert!(!parallelogram.coupler_turns, "{parallelogram:?}");
    }

    /// A tie for the shortest link names the first of the tied links in any unit, ties within
    /// rounding included (as every other comparison of the classification takes them): the
    /// kite of input and coupler 100 mm, ground and output 300 mm names the input; declared in
    /// metres from its joints' coordinates, the coupler `0.3 - 0.2` is one rounding shorter
    /// than the input `0.1`, and the coupler was named (the output `0.4 - 0.1` is one rounding
    /// longer than the ground). The rest of the classification was the same.
    #[test]
    fn a_tie_within_rounding_names_the_first_shortest_link() {
        let mm = grashof(FourBarLinks { ground: 300.0, input: 100.0, coupler: 100.0, output: 300.0 }).unwrap();
        let (input, coupler) = (0.1, 0.3 - 0.2);
        assert!(coupler < input, "the coupler is one rounding shorter in metres");
        let m = grashof(FourBarLinks { ground: 0.3, input, coupler, output: 0.4 - 0.1 }).unwrap();
        assert_eq!((mm.class, mm.shortest), (GrashofClass::ChangePoint, Link::Input), "{mm:?}");
        assert_eq!((m.class, m.shortest), (mm.class, mm.shortest), "{m:?}");
        assert_eq!(
            (m.input_turns, m.output_turns, m.coupler_turns),
            (mm.input_turns, mm.output_turns, mm.coupler_turns)
        );
        // A parallelogram whose ground is computed `0.1 + 0.2`, one rounding above its coupler
        // 0.3, and whose output 0.1 is one rounding above its input `0.3 - 0.2`: the input.
        let p = grashof(FourBarLinks { ground: 0.1 + 0.2, input: 0.3 - 0.2, coupler: 0.3, output: 0.1 }).unwrap();
        let q = grashof(FourBarLinks { ground: 0.3, input: 0.1, coupler: 0.3, output: 0.3 - 0.2 }).unwrap();
        assert_eq!((p.shortest, q.shortest), (Link::Input, Link::Input), "{p:?} {q:?}");
    }

    #[test]
    fn bad_lengths_are_errors() {
        let ok = FourBarLinks { ground: 1.0, input: 1.0, coupler: 1.0, output: 1.0 };
        assert!(grashof(FourBarLinks { input: f64::NAN, ..ok }).is_err());
        assert!(grashof(FourBarLinks { input: -1.0, ..ok }).is_err());
        assert!(grashof(FourBarLinks { ground: 3.5, ..ok }).is_err());
    }
}
