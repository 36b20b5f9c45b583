//! The default drawing's description (`Mechanism::DRAWING`, read by
//! `kinloop::drawing::Description`) against each fixture mechanism's loops: every joint it
//! draws is a loop point computed here by hand, as the partial sum of the declared vectors
//! from the parameter values and the solved unknowns, and each loop's closing point agrees with
//! the sum along its other side. The descriptions of the gallery's mechanisms are pinned in
//! `tests/kinematics/drawing_descriptions.txt` (regenerate with `KINLOOP_BLESS=1` and review the
//! diff).

use kinloop::Mechanism;
use kinloop::drawing::{Description, SegmentKind};
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::roller_edger::RollerEdger;
use kinloop_fixtures::*;
use std::collections::BTreeMap;

/// Joints against hand-computed points: the tape and the hand sums round differently (a few
/// ulps of the links' size), and a closing point computed along the other side of its loop
/// differs by the solve's residual (`tol::SOLVE` relative); 1e-9 of the mechanism's size bounds
/// both with room and is what a drawing needs (far below a pixel).
const DRAWN: f64 = 1e-9;

fn polar(l: f64, a: f64) -> [f64; 2] {
    [l * a.cos(), l * a.sin()]
}

fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// Every joint of `m`'s description at `(x, q)` equals the point of that name in `expected`,
/// and every expected point is a joint; `also` are pairs of points that must coincide (a
/// closing point along the loop's other side).
fn check<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    m: &M,
    x: [f64; NI],
    q: [f64; N],
    expected: &[(&str, [f64; 2])],
    also: &[([f64; 2], [f64; 2])],
) {
    let d = Description::of::<M, N, NI, NO>().expect("the macro's description reads");
    let at = d.evaluate(&m.param_values(), &x, &q).expect("evaluates");
    let size = m.param_values().iter().fold(0.0f64, |s, p| s.max(p.abs()));
    let want: BTreeMap<&str, [f64; 2]> = expected.iter().copied().collect();
    let got: BTreeMap<&str, [f64; 2]> =
        d.joints.iter().map(|j| j.name.as_str()).zip(at.joints.iter().copied()).collect();
    assert_eq!(got.keys().collect::<Vec<_>>(), want.keys().collect::<Vec<_>>(), "{}: the joints", M::NAME);
    for (name, p) in &want {
        let g = got[name];
        let err = (g[0] - p[0]).hypot(g[1] - p[1]);
        assert!(err <= DRAWN * size, "{} joint {name}: {g:?} against {p:?}", M::NAME);
    }
    for (a, b) in also {
        assert!((a[0] - b[0]).hypot(a[1] - b[1]) <= DRAWN * size, "{}: {a:?} against {b:?}", M::NAME);
    }
}

#[test]
fn rhombic_drive_joints_are_its_loop_points() {
    let m = RhombicDrive::default();
    for phi1 in [0.3, 1.7, 4.0] {
        let s = m.solve(phi1).unwrap().q;
        let a = [0.0, m.e_p];
        let b = add(a, polar(m.r_p, phi1));
        let d = add(a, polar(m.r_b, phi1 + m.gamma));
        let (c, f) = ([s.x_c, 0.0], [s.x_f, m.de]);
        let expected = [
            ("origin", [0.0, 0.0]),
            ("oabco.l1", a),
            ("oabco.l2", b),
            ("oabco.r1", c),
            ("oadff1o.l2", d),
            ("oadff1o.r1", f),
            ("s1", add(a, polar(m.l_as1, phi1 + m.psi_s1))),
            ("s2", add(c, polar(m.l_cs2, s.phi2))),
            ("s4", add(f, polar(m.l_fs4, s.phi4))),
        ];
        let also = [(b, add(c, polar(m.l_p, s.phi2))), (d, add(f, polar(m.l_b, s.phi4)))];
        check(&m, [phi1], s.into(), &expected, &also);
    }
}

#[test]
fn developed_rod_drives_joints_are_their_loop_points() {
    let m = DisplacerRodDrive::default();
    for phi1 in [0.3, 1.7, 4.0] {
        let s = m.solve(phi1).unwrap().q;
        let a = [0.0, m.e_p];
        let b = add(a, polar(m.r, phi1));
        let (c, f) = ([s.x_c, 0.0], [s.x_f, m.de]);
        let d = add(f, polar(m.l_fd, s.phi4 + m.gamma_b));
        let expected = [
            ("origin", [0.0, 0.0]),
            ("oabff1o.l1", a),
            ("oabff1o.l2", b),
            ("oabff1o.r1", f),
            ("ocdff1o.l1", c),
            ("d", d),
        ];
        let also = [(b, add(f, polar(m.l_b, s.phi4))), (d, add(c, polar(m.l_p, s.phi2)))];
        check(&m, [phi1], s.into(), &expected, &also);
    }
    let m = WorkingRodDrive::default();
    for phi1 in [0.3, 1.7, 4.0] {
        let s = m.solve(phi1).unwrap().q;
        let a = [0.0, m.e_p];
        let b = add(a, polar(m.r, phi1));
        let (c, f) = ([s.x_c, 0.0], [s.x_f, m.de]);
        let d = add(c, polar(m.l_cd, s.phi2 + m.gamma_p));
        let expected =
            [("origin", [0.0, 0.0]), ("oabco.l1", a), ("oabco.l2", b), ("oabco.r1", c), ("of1fdco.l1", f), ("d", d)];
        let also = [(b, add(c, polar(m.l_p, s.phi2))), (d, add(f, polar(m.l_b, s.phi4)))];
        check(&m, [phi1], s.into(), &expected, &also);
    }
}

#[test]
fn gear_lever_joints_are_its_loop_points() {
    let m = GearLever::default();
    for alpha in [0.3, 1.7, 4.0] {
        let s = m.solve(alpha).unwrap().q;
        // Directions from the Y axis: `(sin a, cos a)`.
        let centre = [m.l_c * alpha.sin(), m.l_c * alpha.cos()];
        let turn = (1.0 - m.u) * alpha;
        let pin = add(centre, [m.l_p * turn.sin(), m.l_p * turn.cos()]);
        let expected = [("origin", [0.0, 0.0]), ("oab.l1", centre), ("b", pin)];
        let also = [(pin, [s.s * s.phi.sin(), s.s * s.phi.cos()])];
        check(&m, [alpha], s.into(), &expected, &also);
    }
}

#[test]
fn roller_edger_joints_are_its_loop_points_with_the_second_loop_from_its_own_pivot() {
    let m = RollerEdger::default();
    for t in [0.0, 2.0, 5.0] {
        let s = m.solve(t).unwrap().q;
        let a = polar(m.v1 * t + m.l1, s.phi1);
        let o3 = polar(m.l5, m.alpha);
        // The second loop runs O2 B A O3: its first point is O2 = O3 - l6 @ beta.
        let o2 = sub(o3, polar(m.l6, m.beta));
        let b = add(o2, polar(m.s2 + m.l2, s.phi2));
        let expected =
            [("origin", [0.0, 0.0]), ("o1ao3.l1", a), ("o1ao3.l2", o3), ("o2bao3.start", o2), ("o2bao3.l1", b)];
        let also = [(o3, add(a, polar(m.l3, s.phi3))), (a, add(b, polar(m.l4, s.phi4)))];
        check(&m, [t], s.into(), &expected, &also);
    }
}

#[test]
fn class_four_joints_are_its_loop_points() {
    let m = ClassFour::default();
    for phi in [0.3, 1.7, 4.0] {
        let s = m.solve(phi).unwrap().q;
        let (a, b) = (polar(m.oa, phi), [m.xb, m.yb]);
        let c = add(a, polar(m.ac, s.th1));
        let e = add(a, polar(m.ae, s.th1 + m.alpha_a));
        let d = add(b, polar(m.bd, s.th2));
        let f = add(b, polar(m.bf, s.th2 + m.alpha_b));
        let expected = [("origin", [0.0, 0.0]), ("acdb.l1", a), ("acdb.r1", b), ("c", c), ("d", d), ("e", e), ("f", f)];
        let also = [(d, add(c, polar(m.cd, s.psi1))), (f, add(e, polar(m.ef, s.psi2)))];
        check(&m, [phi], s.into(), &expected, &also);
    }
}

#[test]
fn textbook_linkages_joints_are_their_loop_points() {
    let m = FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 };
    for phi in [0.3, 1.7, 4.0] {
        let s = m.solve(phi).unwrap().q;
        let b = polar(m.a, phi);
        let c = add(b, polar(m.b, s.beta));
        let expected = [("origin", [0.0, 0.0]), ("abcd.l1", b), ("abcd.r1", [m.d, 0.0]), ("pc", c)];
        check(&m, [phi], s.into(), &expected, &[(c, add([m.d, 0.0], polar(m.c, s.gamma)))]);
    }
    let m = SliderCrank { r: 1.0, l: 3.0, e: 0.2 };
    for phi in [0.3, 1.7, 4.0] {
        let s = m.solve(phi).unwrap().q;
        let b = polar(m.r, phi);
        let expected = [("origin", [0.0, 0.0]), ("oabo.l1", b), ("oabo.r1", [s.x, m.e])];
        check(&m, [phi], s.into(), &expected, &[(b, add([s.x, m.e], polar(m.l, s.psi)))]);
    }
    let m = FiveBar::default();
    for (t1, t2) in [(1.4, 1.0), (1.2, 0.8), (1.6, 1.3)] {
        let s = m.solve([t1, t2]).unwrap().q;
        let b = polar(m.a, t1);
        let p = add(b, polar(m.b, s.phi2));
        let e = add([m.d, 0.0], polar(m.e, t2));
        let expected = [("origin", [0.0, 0.0]), ("abcde.l1", b), ("abcde.r1", [m.d, 0.0]), ("abcde.r2", e), ("pc", p)];
        check(&m, [t1, t2], s.into(), &expected, &[(p, add(e, polar(m.c, s.phi3)))]);
    }
}

/// The slotted lever's rocker is one body: the tip, reached from the rocker's pivot by a
/// vector turning with the slot, is a joint of a plate that holds the slot's turning guide,
/// so the drawing draws the rocker rigid and the tip on it, without a note.
#[test]
fn a_slotted_levers_tip_is_on_its_rocker_with_the_guide() {
    let m = SlottedLever::default();
    let d = Description::of::<SlottedLever, 2, 1, 2>().expect("reads");
    assert!(d.notes.is_empty(), "{:?}", d.notes);
    let (pivot, tip) = (d.joint("slot.r1").unwrap(), d.joint("tip").unwrap());
    let slot = d.segments.iter().position(|s| s.kind == SegmentKind::Slider { fixed_guide: false }).unwrap();
    assert_eq!(d.segments[slot].from, pivot);
    let rocker: Vec<_> = d.plates.iter().filter(|p| !p.guides.is_empty()).collect();
    assert_eq!(rocker.len(), 1, "{d}");
    assert_eq!(rocker[0].joints, [pivot, tip]);
    assert_eq!(rocker[0].guides, [slot]);
    for phi in [0.3, 1.7, 4.0] {
        let s = m.solve(phi).unwrap().q;
        let o = [0.0, -m.d];
        let b = polar(m.r, phi);
        let expected = [("origin", [0.0, 0.0]), ("slot.l1", b), ("slot.r1", o), ("tip", add(o, polar(m.l, s.theta)))];
        check(&m, [phi], s.into(), &expected, &[(b, add(o, polar(s.s, s.theta)))]);
    }
}

fn text<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(_: &M) -> String {
    format!("== {}\n{}", M::NAME, Description::of::<M, N, NI, NO>().expect("reads"))
}

/// The gallery's descriptions in words (joints, segments with their kinds, plates, notes),
/// pinned: a change to how declarations are drawn shows in the diff of the file.
#[test]
fn gallery_descriptions_are_pinned() {
    let all = [
        text(&RhombicDrive::default()),
        text(&StirlingEngine::default()),
        text(&DisplacerRodDrive::default()),
        text(&WorkingRodDrive::default()),
        text(&GearLever::default()),
        text(&RollerEdger::default()),
        text(&ClassFour::default()),
        text(&FourBar { a: 1.0, b: 3.0, c: 2.5, d: 3.2 }),
        text(&SliderCrank { r: 1.0, l: 3.0, e: 0.2 }),
        text(&FiveBar::default()),
        text(&SlottedLever::default()),
    ]
    .join("\n");
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/kinematics/drawing_descriptions.txt");
    if std::env::var_os("KINLOOP_BLESS").is_some() {
        std::fs::write(&path, &all).expect("writable");
    }
    let pinned = std::fs::read_to_string(&path).expect("the pinned descriptions");
    assert_eq!(all, pinned, "the descriptions changed: rerun with KINLOOP_BLESS=1 and review the diff");
}
