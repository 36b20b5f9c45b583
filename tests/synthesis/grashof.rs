//! Every candidate of a four-bar whose links are named carries its Grashof class and its
//! smallest transmission angle over the input's range: on hand-made designs of each class,
//! against the textbook inequalities and a brute-force sweep of the transmission angle.

use super::mechanisms::{CouplerFourBar, four_bar_pose};
use kinloop::metrics::GrashofClass;
use kinloop::synthesis::{Candidate, Constraints, Design, Problem, Search, Task, grashof_code};
use std::f64::consts::{PI, TAU};

/// The candidate of the design `p = [a, b, c, d, e, alpha]` (input, coupler, output, ground)
/// through its own coupler points at `phis` (only `e` varies; refined from its value).
fn candidate(p: [f64; 6], phis: &[f64]) -> Candidate {
    let poses: Vec<([f64; 2], [f64; 2])> = phis.iter().map(|&x| four_bar_pose(p, x, 1.0)).collect();
    let task = Task::path("p", poses.iter().map(|(t, _)| *t)).timed(phis.to_vec());
    let [a, b, c, d, e, alpha] = p;
    let problem =
        Problem::new(CouplerFourBar { a, b, c, d, e, alpha }, &Design::new().var("e", 0.5 * e, 2.0 * e), &task)
            .unwrap()
            .with_guesses(poses.iter().map(|(_, q)| *q).collect())
            .unwrap()
            .with_constraints(&Constraints::default().with_four_bar("d", "a", "b", "c"))
            .unwrap();
    let c = Search::default().refine(&problem, &[e]).unwrap();
    assert!(c.max_error < 1e-13 && c.is_valid(), "{c:?}");
    c
}

/// The textbook rule (Grashof 1883; e.g. Norton, Design of Machinery, ch. 2): with `s` the
/// shortest, `l` the longest, `p`, `q` the others, `s + l < p + q` is a Grashof linkage whose
/// class follows from where the shortest link is; `s + l > p + q` a triple rocker; equal a
/// change point.
fn textbook([a, b, c, d]: [f64; 4]) -> GrashofClass {
    let mut sorted = [a, b, c, d];
    sorted.sort_by(f64::total_cmp);
    let (s, l, pq) = (sorted[0], sorted[3], sorted[1] + sorted[2]);
    if s + l == pq {
        GrashofClass::ChangePoint
    } else if s + l > pq {
        GrashofClass::TripleRocker
    } else if s == d {
        GrashofClass::DoubleCrank
    } else if s == a {
        GrashofClass::CrankRocker
    } else if s == c {
        GrashofClass::RockerCrank
    } else {
        GrashofClass::DoubleRocker
    }
}

/// The smallest acute angle between coupler and output over a turn of the input, by
/// intersecting circles at 36000 input angles (where it assembles).
fn brute_force_transmission([a, b, c, d]: [f64; 4]) -> f64 {
    (0..36000)
        .filter_map(|i| {
            let phi = TAU * i as f64 / 36000.0;
            let (bx, by) = (a * phi.cos(), a * phi.sin());
            let e = (d - bx).hypot(by);
            if e > b + c || e < (b - c).abs() {
                return None;
            }
            // The angle at C of the triangle B C D, by the law of cosines.
            let mu = ((b * b + c * c - e * e) / (2.0 * b * c)).clamp(-1.0, 1.0).acos();
            Some(mu.min(PI - mu))
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn every_class_on_hand_made_designs() {
    // [a, b, c, d] (input, coupler, output, ground), the coupler point, and input angles where
    // each assembles (a rocking input within its range).
    let designs: [([f64; 4], &[f64], GrashofClass); 6] = [
        ([1.0, 3.2, 2.4, 3.1], &[0.5, 1.5, 2.5], GrashofClass::CrankRocker),
        ([3.0, 3.5, 3.2, 1.0], &[0.5, 1.5, 2.5], GrashofClass::DoubleCrank),
        ([3.0, 3.5, 1.0, 3.2], &[1.0, 1.2, 1.4], GrashofClass::RockerCrank),
        ([3.0, 1.0, 3.2, 3.5], &[0.8, 1.0, 1.2], GrashofClass::DoubleRocker),
        ([1.0, 1.5, 1.3, 2.0], &[0.2, 0.6, 1.0], GrashofClass::TripleRocker),
        ([1.0, 3.0, 2.0, 2.0], &[0.5, 1.0, 1.5], GrashofClass::ChangePoint),
    ];
    for (links, phis, class) in designs {
        assert_eq!(textbook(links), class, "{links:?}");
        let [a, b, c, d] = links;
        let got = candidate([a, b, c, d, 0.8, 0.3], phis).four_bar.unwrap();
        assert_eq!(got.class, class, "{links:?}");
        let mut sorted = links;
        sorted.sort_by(f64::total_cmp);
        let margin = (sorted[0] + sorted[3] - sorted[1] - sorted[2]) / links.iter().sum::<f64>();
        assert!((got.margin - margin).abs() < 1e-15, "{links:?}: {}", got.margin);
        let turns = matches!(class, GrashofClass::CrankRocker | GrashofClass::DoubleCrank | GrashofClass::ChangePoint);
        if turns {
            // The grid's 0.01 degree step misses the minimum by at most (step)^2 times the
            // angle's curvature: well below 1e-6 rad here.
            let brute = brute_force_transmission(links);
            assert!((got.min_transmission - brute).abs() < 1e-6, "{links:?}: {} vs {brute}", got.min_transmission);
        } else {
            assert_eq!(got.min_transmission, 0.0, "a rocking input meets its limit positions");
        }
    }
    // The crank-rocker's textbook closed form: the smaller of the angles at phi = 0 and pi.
    let cr = candidate([1.0, 3.2, 2.4, 3.1, 0.8, 0.3], &[0.5, 1.5, 2.5]).four_bar.unwrap();
    let mu = |e: f64| ((3.2f64 * 3.2 + 2.4 * 2.4 - e * e) / (2.0 * 3.2 * 2.4)).acos();
    let want = [mu(3.1 - 1.0), mu(3.1 + 1.0)].map(|m| m.min(PI - m));
    assert!((cr.min_transmission - want[0].min(want[1])).abs() < 1e-15);
}

#[test]
fn the_class_is_a_column_of_the_table_and_names_are_checked() {
    let phis = [0.5, 1.5, 2.5];
    let poses: Vec<[f64; 2]> = phis.iter().map(|&x| four_bar_pose([1.0, 3.2, 2.4, 3.1, 0.8, 0.3], x, 1.0).0).collect();
    let task = Task::path("p", poses).timed(phis);
    let m = CouplerFourBar { a: 1.0, b: 3.2, c: 2.4, d: 3.1, e: 0.8, alpha: 0.3 };
    let problem = Problem::new(m, &Design::new().var("e", 0.5, 1.5), &task).unwrap();
    let named = problem.clone().with_constraints(&Constraints::default().with_four_bar("d", "a", "b", "c")).unwrap();
    let report = Search::default().with_starts(0..2).run(&named).unwrap();
    let table = report.table().unwrap();
    let code = table.column("grashof").unwrap();
    assert_eq!(code[0], f64::from(grashof_code(GrashofClass::CrankRocker)));
    assert!(table.column("min_transmission_range").unwrap()[0] > 0.5);
    // Without the names, no such column.
    let plain = Search::default().with_starts(0..2).run(&problem).unwrap();
    assert!(plain.table().unwrap().column("grashof").is_none());
    assert!(plain.best().unwrap().four_bar.is_none());
    // Named, but no candidate (a crank too long for the rest, `a - d > b + c`): the columns
    // still, as the problem's kind says, not as its candidates happen to.
    let none = Problem::new(m, &Design::new().var("a", 50.0, 60.0), &task).unwrap();
    let none = none.with_constraints(&Constraints::default().with_four_bar("d", "a", "b", "c")).unwrap();
    let report = Search::default().with_starts(0..2).run(&none).unwrap();
    assert_eq!((report.candidates.len(), report.four_bar), (0, true));
    assert_eq!(report.table().unwrap().column("grashof"), Some(Vec::new()));
    // A name that is no parameter, and a link named twice.
    let e = problem.clone().with_constraints(&Constraints::default().with_four_bar("d", "a", "b", "q")).unwrap_err();
    assert!(matches!(&e, kinloop::synthesis::SynthesisError::UnknownVariable { name, .. } if name == "q"), "{e}");
    let e = problem.with_constraints(&Constraints::default().with_four_bar("d", "a", "a", "c")).unwrap_err();
    assert!(matches!(e, kinloop::synthesis::SynthesisError::DuplicateVariable { .. }));
}
