//! Closed-form blocks against Newton: every mechanism of the fixtures and tests that has a
//! closed-form block is declared a second time with `#[kinloop(newton)]` (its Newton twin), and
//! both are swept over whole turns in every assembly mode, from the previous position as the
//! guess (as a sweep does) and through the runtime's branch-safe `Sweep`.
//!
//! The Newton twin iterates to a residual of 1e-14 (rounding level for these unit-size
//! mechanisms), so the two differ only by rounding amplified by the conditioning: positions
//! agree to 1e-13, analogs to 1e-11 relative. Where the closed form has no root, the error is
//! the same typed `NoAssembly` as Newton's.

use crate::support::{assert_singular_block_0, newton_to_rounding, tol};
use kinloop::{Error, Kin, Mechanism, NewtonConfig, QuantityKind, Sweep, SweepConfig};
use kinloop_fixtures::gear_lever::{GEAR_LEVER_TEXT, GearLever};
use kinloop_fixtures::roller_edger::{ROLLER_EDGER_TEXT, RollerEdger};
use kinloop_fixtures::{ClassFour, RHOMBIC_DRIVE_TEXT, RhombicDrive};
use std::f64::consts::{PI, TAU};

/// Declares the Newton twin `$name` of a fixture from a copy of its body, and `$body_text`, the
/// body's text, which [`newton_twins_are_the_fixtures`] finds in the fixture's declaration.
macro_rules! newton_twin {
    ($body_text:ident, $(#[doc = $doc:literal])* pub struct $name:ident { $($body:tt)* }) => {
        kinloop::mechanism! {
            $(#[doc = $doc])*
            #[kinloop(newton)]
            pub struct $name { $($body)* }
        }
        const $body_text: &str = stringify!($($body)*);
    };
}

newton_twin! {
    RHOMBIC_BODY,
    /// Newton twin of the fixtures' rhombic drive.
    pub struct RhombicDriveNewton {
        params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, de = 0.9, gamma = 0.7,
               l_as1 = 0.3, psi_s1 = 0.35, l_cs2 = 1.2, l_fs4 = 1.4;
        input phi1;
        unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
        /// Centre of mass of the crank.
        point s1 = (0, e_p) + l_as1 @ (phi1 + psi_s1);
        /// Centre of mass of the working rod.
        point s2 = (x_c, 0) + l_cs2 @ phi2;
        /// Centre of mass of the displacer rod.
        point s4 = (x_f, de) + l_fs4 @ phi4;
        /// Distance from the working piston to the displacer along the X axis.
        output gap = x_f - x_c;
    }
}

newton_twin! {
    ROLLER_EDGER_BODY,
    /// Newton twin of the fixtures' roller edger.
    pub struct RollerEdgerNewton {
        params l1 = 0.9, l3 = 0.6, l5 = 1.2, alpha = 0.2, v1 = 0.05,
               l2 = 1.0, s2 = 0.1, l4 = 0.7, l6 = 1.4, beta = 0.9;
        input t;
        unknowns phi1 = 1.2, phi3 = -0.8, phi2 = 2.0, phi4 = 0.5;
        let s1 = v1 * t;
        loop o1ao3:  (s1 + l1) @ phi1 + l3 @ phi3 == l5 @ alpha;
        loop o2bao3: (s2 + l2) @ phi2 + l4 @ phi4 + l3 @ phi3 == l6 @ beta;
    }
}

newton_twin! {
    GEAR_LEVER_BODY,
    /// Newton twin of the fixtures' gear-lever drive.
    pub struct GearLeverNewton {
        params l_c = 2.0, l_p = 1.3, u = 3.0;
        input alpha;
        unknowns s = l_c + l_p, phi = 0;
        let pin = (l_c * sin(alpha), l_c * cos(alpha))
                + (l_p * sin((1 - u) * alpha), l_p * cos((1 - u) * alpha));
        loop oab: pin == s * (sin(phi), cos(phi));
        /// The planet pin.
        point b = pin;
    }
}

/// The twins cannot drift from the fixtures they stand for: each body is in the fixture's text.
#[test]
fn newton_twins_are_the_fixtures() {
    for (body, fixture) in
        [(RHOMBIC_BODY, RHOMBIC_DRIVE_TEXT), (ROLLER_EDGER_BODY, ROLLER_EDGER_TEXT), (GEAR_LEVER_BODY, GEAR_LEVER_TEXT)]
    {
        // `stringify!` breaks long lines where it likes: compare without white space.
        let bare = |s: &str| s.split_whitespace().collect::<String>();
        assert!(bare(fixture).contains(&bare(body)), "twin body\n{body}\nnot in the fixture\n{fixture}");
    }
}

with_newton_twin! {
    /// Grashof crank-rocker with a coupler point (RRR dyad).
    pub struct FourBar, FourBarNewton {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2, pc = 1.4, pa = 0.5;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point p = a @ phi + pc @ (beta + pa);
        output transmission = gamma - beta;
    }
}

with_newton_twin! {
    /// Offset slider-crank (angle equation, then the slider linearly).
    pub struct SliderCrank, SliderCrankNewton {
        params r = 1.0, l = 3.0, e = 0.4;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oabo: r @ phi == (x, e) + l @ psi;
    }
}

with_newton_twin! {
    /// Slider-crank whose slide is inclined by `tilt` and offset by `e`: the rod angle and the
    /// slider are coupled in one block (RRP).
    pub struct TiltedSlider, TiltedSliderNewton {
        params r = 1.0, l = 2.6, e = 0.3, tilt = 0.5;
        input phi;
        unknowns psi = 0, x = 3;
        loop oabo: r @ phi == x @ tilt + e @ (tilt + pi / 2) + l @ psi;
    }
}

with_newton_twin! {
    /// Whitworth quick return: the slotted rocker through the crank pin (length and angle).
    pub struct SlottedRocker, SlottedRockerNewton {
        params r = 1.0, h = 1.8;
        input phi;
        unknowns s = 2.8, theta = 1.57;
        loop oab: (0, h) + r @ phi == s @ theta;
        point tip = 3 @ theta;
    }
}

with_newton_twin! {
    /// The slotted rocker with its length counted in half units (`2 s` along the slot): the
    /// length's direction has the constant magnitude 2, by which the closed form divides.
    pub struct HalfUnitRocker, HalfUnitRockerNewton {
        params r = 1.0, h = 1.8;
        input phi;
        unknowns s = 1.4, theta = 1.57;
        loop oab: (0, h) + r @ phi == (2 * s) @ theta;
    }
}

with_newton_twin! {
    /// A length along a direction whose magnitude changes with its angle (`(cos t, 2 sin t)`,
    /// an ellipse's parametrisation): the closed form's general division by `|w(t)|²`.
    pub struct EllipticRocker, EllipticRockerNewton {
        params r = 1.0, h = 1.8;
        input phi;
        unknowns s = 1.4, theta = 1.57;
        loop oab: (0, h) + r @ phi == s * (cos(theta), 2 * sin(theta));
    }
}

with_newton_twin! {
    /// Watt-II six-bar: two four-bars in series, the rocker of the first driving the second
    /// through a rigid offset (two RRR dyads).
    pub struct SixBar, SixBarNewton {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2, c2 = 1.2, delta = 0.6, e = 2.8, f = 4.6, g = 1.0, h = 2.2;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, eps = 0.3, eta = 1.8;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop second: (d, 0) + c2 @ (gamma + delta) + e @ eps == (f, g) + h @ eta;
    }
}

with_newton_twin! {
    /// Five-bar with two inputs (one RRR dyad).
    pub struct FiveBar, FiveBarNewton {
        params a = 1.0, b = 2.5, c = 2.2, d = 1.5, e = 1.2;
        inputs th1, th2;
        unknowns phi2 = 1.0, phi3 = 2.0;
        loop abcde: a @ th1 + b @ phi2 == (d, 0) + e @ th2 + c @ phi3;
        point pc = a @ th1 + b @ phi2;
    }
}

with_newton_twin! {
    /// A dyad whose links carry constant offset angles, the second written with its components
    /// swapped (a reflection of its angle): the branch rule's `K00 cos σ + K01 sin σ` with both
    /// coefficients non-zero and `σ = q1 + q0`.
    pub struct OffsetDyad, OffsetDyadNewton {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2, alpha = 0.4, delta = -0.3;
        input phi;
        unknowns u = 0.1, v = 1.2;
        loop l: a @ phi + b @ (u + alpha) == (d, 0) + c * (sin(v + delta), cos(v + delta));
    }
}

fn assert_agree<const N: usize, const NI: usize, const NO: usize>(at: &str, a: &Kin<N, NI, NO>, b: &Kin<N, NI, NO>) {
    for u in 0..N {
        // Relative tolerances (`rel`): angles absolutely, lengths relative to their size.
        assert_close!(a.q[u], b.q[u], rel = 1e-13, "q[{u}] {at}, closed form vs Newton");
        for i in 0..NI {
            let (x, y) = (a.dq[u][i], b.dq[u][i]);
            assert_close!(x, y, rel = 1e-11, "dq[{u}][{i}] {at}, closed form vs Newton");
            for j in 0..NI {
                let (x, y) = (a.d2q[u][i][j], b.d2q[u][i][j]);
                assert_close!(x, y, rel = 1e-11, "d2q[{u}][{i}][{j}] {at}, closed form vs Newton");
            }
        }
    }
    for o in 0..NO {
        assert_close!(a.out[o], b.out[o], rel = 1e-13, "out[{o}] {at}, closed form vs Newton");
        for i in 0..NI {
            assert_close!(a.dout[o][i], b.dout[o][i], rel = 1e-11, "dout[{o}][{i}] {at}, closed form vs Newton");
        }
    }
}

/// Both mechanisms over `samples` steps from `from` to `to`, in every assembly mode the Newton
/// twin finds at `from`: point steps from the previous position, then the runtime's sweep.
/// Returns the number of assembly modes compared.
fn agree_over<A, B, const N: usize, const NI: usize, const NO: usize>(
    a: &A,
    b: &B,
    from: [f64; NI],
    to: [f64; NI],
    samples: usize,
) -> usize
where
    A: Mechanism<N, NI, NO>,
    B: Mechanism<N, NI, NO>,
{
    let modes = kinloop::paths::modes::assembly_modes(b, &from, 64, &newton_to_rounding()).unwrap();
    assert!(!modes.is_empty(), "{}: no assembly mode at {from:?}", B::NAME);
    for mode in &modes {
        let (mut ga, mut gb) = (mode.q, mode.q);
        for k in 0..=samples {
            let t = k as f64 / samples as f64;
            let x: [f64; NI] = std::array::from_fn(|i| from[i] + t * (to[i] - from[i]));
            let at = format!("{} at {x:?} (mode from {:?})", A::NAME, mode.q);
            let ka = a.kinematics_flat(&x, &ga, &NewtonConfig::default()).unwrap_or_else(|e| panic!("{at}: {e}"));
            let kb = b.kinematics_flat(&x, &gb, &newton_to_rounding()).unwrap_or_else(|e| panic!("Newton {at}: {e}"));
            assert_agree(&at, &ka, &kb);
            ga = ka.q;
            gb = kb.q;
        }
        let sa: Vec<Kin<N, NI, NO>> =
            Sweep::new(a, from, to, samples + 1, mode.q).unwrap().collect::<Result<_, _>>().unwrap();
        let newton = SweepConfig::default().with_newton(newton_to_rounding());
        let sb: Vec<Kin<N, NI, NO>> = Sweep::new(b, from, to, samples + 1, mode.q)
            .unwrap()
            .with_config(newton)
            .collect::<Result<_, _>>()
            .unwrap();
        assert_eq!(sa.len(), sb.len());
        for (ka, kb) in sa.iter().zip(&sb) {
            assert_agree(&format!("{} sweep at {:?}", A::NAME, ka.x), ka, kb);
        }
    }
    modes.len()
}

#[test]
fn decomposition_names_each_closed_form() {
    let d = RhombicDrive::DECOMPOSITION;
    assert!(d.contains("(closed form, angle equation): phi2 <- oabco.y"), "{d}");
    assert!(d.contains("(closed form, angle equation): phi4 <- oadff1o.y"), "{d}");
    assert!(d.contains("(linear, 1x1): x_c <- oabco.x"), "{d}");
    assert!(RhombicDriveNewton::DECOMPOSITION.contains("(Newton, 1x1): phi2 <- oabco.y"));
    let d = FourBar::DECOMPOSITION;
    assert!(d.contains("(closed form, RRR dyad): beta, gamma <- abcd.x, abcd.y"), "{d}");
    assert!(FourBarNewton::DECOMPOSITION.contains("(Newton, 2x2): beta, gamma"));
    assert!(TiltedSlider::DECOMPOSITION.contains("(closed form, angle and slider): psi, x"));
    assert!(SlottedRocker::DECOMPOSITION.contains("(closed form, length and angle): s, theta"));
    assert!(GearLever::DECOMPOSITION.contains("(closed form, length and angle): s, phi"));
    assert_eq!(SixBar::DECOMPOSITION.matches("closed form, RRR dyad").count(), 2, "{}", SixBar::DECOMPOSITION);
    assert_eq!(RollerEdger::DECOMPOSITION.matches("closed form, RRR dyad").count(), 2);
    assert!(FiveBar::DECOMPOSITION.contains("closed form, RRR dyad"));
    // The class IV group has no closed form: one Newton block.
    assert!(ClassFour::DECOMPOSITION.contains("(Newton, 4x4)"), "{}", ClassFour::DECOMPOSITION);
}

#[test]
fn rhombic_drive_agrees_with_newton() {
    let n = agree_over(&RhombicDrive::default(), &RhombicDriveNewton::default(), [0.0], [TAU], 720);
    assert_eq!(n, 4, "two rods, each on either side of its crank pin");
}

#[test]
fn roller_edger_agrees_with_newton() {
    let n = agree_over(&RollerEdger::default(), &RollerEdgerNewton::default(), [0.0], [6.0], 600);
    assert_eq!(n, 4);
}

#[test]
fn gear_lever_agrees_with_newton() {
    let n = agree_over(&GearLever::default(), &GearLeverNewton::default(), [0.0], [TAU], 720);
    assert_eq!(n, 2, "the rocker's length on either side of the pivot");
}

#[test]
fn four_bar_and_six_bar_agree_with_newton() {
    assert_eq!(agree_over(&FourBar::default(), &FourBarNewton::default(), [0.0], [TAU], 720), 2);
    assert_eq!(agree_over(&SixBar::default(), &SixBarNewton::default(), [0.0], [TAU], 720), 4);
}

#[test]
fn slider_cranks_and_slotted_rocker_agree_with_newton() {
    assert_eq!(agree_over(&SliderCrank::default(), &SliderCrankNewton::default(), [0.0], [TAU], 720), 2);
    assert_eq!(agree_over(&TiltedSlider::default(), &TiltedSliderNewton::default(), [0.0], [TAU], 720), 2);
    assert_eq!(agree_over(&SlottedRocker::default(), &SlottedRockerNewton::default(), [0.0], [TAU], 720), 2);
}

#[test]
fn a_length_along_a_scaled_or_elliptic_direction_agrees_with_newton() {
    for d in [HalfUnitRocker::DECOMPOSITION, EllipticRocker::DECOMPOSITION] {
        assert!(d.contains("(closed form, length and angle): s, theta"), "{d}");
    }
    assert_eq!(agree_over(&HalfUnitRocker::default(), &HalfUnitRockerNewton::default(), [0.0], [TAU], 720), 2);
    assert_eq!(agree_over(&EllipticRocker::default(), &EllipticRockerNewton::default(), [0.0], [TAU], 720), 2);
}

#[test]
fn a_dyad_with_offset_and_reflected_links_agrees_with_newton() {
    assert!(OffsetDyad::DECOMPOSITION.contains("closed form, RRR dyad"), "{}", OffsetDyad::DECOMPOSITION);
    assert_eq!(agree_over(&OffsetDyad::default(), &OffsetDyadNewton::default(), [0.0], [TAU], 720), 2);
}

#[test]
fn five_bar_agrees_with_newton_along_a_path_of_both_inputs() {
    let n = agree_over(&FiveBar::default(), &FiveBarNewton::default(), [0.2, 0.1], [1.4, 0.9], 400);
    assert_eq!(n, 2);
}

/// The closed form keeps the guess's turn: a guess several turns away gives the same turn back.
#[test]
fn angles_stay_on_the_guess_turn() {
    let m = FourBar::default();
    let k = m.solve(0.3).unwrap();
    for turns in [-3.0, 2.0, 7.0] {
        let mut g = k.q;
        g.beta += turns * TAU;
        g.gamma += turns * TAU;
        let s = m.kinematics(0.3, &g).unwrap();
        assert_close!(s.q.beta - k.q.beta, turns * TAU, tol::SOLVE, "{turns}: {:?}", s.q);
        assert_close!(s.q.gamma - k.q.gamma, turns * TAU, tol::SOLVE, "{turns}: {:?}", s.q);
    }
}

/// Newton from guesses anywhere within +-10 rad of every angle: each block's angles end within
/// half a turn of their guesses, as the closed forms' do, and agree with the closed form solved
/// from the same guess wherever Newton ended in the assembly mode the closed form picks. From
/// such guesses Newton's first steps can be long (a near-singular Jacobian): it used to end up
/// to thousands of turns out, its angles then off by up to 1e-12 from the closed form's modulo
/// a turn; now within a few rounding units of the angles' size.
fn newton_ends_on_the_guess_turn<A, B, const N: usize, const NO: usize>(a: &A, b: &B, x: f64) -> (usize, usize)
where
    A: Mechanism<N, 1, NO>,
    B: Mechanism<N, 1, NO>,
{
    let angle = B::UNKNOWN_KINDS.map(|k| k == QuantityKind::Angle);
    let start = b.kinematics_flat(&[x], &b.guess_flat(&[x]), &NewtonConfig::default()).unwrap().q;
    let (mut same_mode, mut solves) = (0, 0);
    for k in 0..400u32 {
        // A low-discrepancy walk over the box of guesses (each angle in [-10, 10]).
        let guess: [f64; N] = std::array::from_fn(|u| {
            let w = (f64::from(k) * (0.618_034 + 0.414_214 * u as f64)).fract();
            if angle[u] { -10.0 + 20.0 * w } else { start[u] * (0.5 + w) }
        });
        let Ok(n) = b.kinematics_flat(&[x], &guess, &NewtonConfig::default()) else { continue };
        solves += 1;
        for u in (0..N).filter(|&u| angle[u]) {
            assert_close!(n.q[u], guess[u], <= PI, "{} from {guess:?}: {}", B::NAME, n.q[u]);
        }
        let c = a.kinematics_flat(&[x], &guess, &NewtonConfig::default()).unwrap();
        if c.health.det_signs == n.health.det_signs {
            same_mode += 1;
            for u in 0..N {
                let tol = 8.0 * f64::EPSILON * c.q[u].abs().max(1.0);
                assert_close!(n.q[u], c.q[u], <= tol, "{} q[{u}] from {guess:?}: {} vs {}", B::NAME, n.q[u], c.q[u]);
            }
        }
    }
    (same_mode, solves)
}

#[test]
fn newton_from_far_guesses_ends_on_the_guess_turn() {
    for (same_mode, solves) in [
        newton_ends_on_the_guess_turn(&FourBar::default(), &FourBarNewton::default(), 0.7),
        newton_ends_on_the_guess_turn(&SixBar::default(), &SixBarNewton::default(), 0.7),
        newton_ends_on_the_guess_turn(&OffsetDyad::default(), &OffsetDyadNewton::default(), 0.7),
        newton_ends_on_the_guess_turn(&SlottedRocker::default(), &SlottedRockerNewton::default(), 0.7),
    ] {
        // Newton fails from no guess at all, and ends in the closed form's mode from many.
        assert_eq!(solves, 400);
        assert!(same_mode >= 100, "{same_mode} of {solves}");
    }
}

/// A guess so many turns out that an angle cannot be solved to the tolerance on its turn (a
/// billion radians: doubles 1.2e-7 apart) is named as such on both paths, not reported as a
/// failure to converge (the closed form) or to assemble (Newton, whose residual stalls at the
/// rounding of the angle). A hundred thousand turns out is still solved, on the guess's turn.
#[test]
fn an_angle_too_many_turns_out_is_named() {
    fn check<A: Mechanism<2, 1, NO>, B: Mechanism<2, 1, NO>, const NO: usize>(a: &A, b: &B, angles: &[usize]) {
        let at = a.kinematics_flat(&[0.7], &a.guess_flat(&[0.7]), &NewtonConfig::default()).unwrap().q;
        // `at` with its angles moved `turns` turns out.
        let far = |turns: f64| -> [f64; 2] {
            std::array::from_fn(|u| if angles.contains(&u) { at[u] + turns * TAU } else { at[u] })
        };
        let cfg = NewtonConfig::default();
        for (path, r) in [
            ("closed form", a.kinematics_flat(&[0.7], &far(1.6e8), &cfg)),
            ("Newton", b.kinematics_flat(&[0.7], &far(1.6e8), &cfg)),
        ] {
            match r {
                Err(Error::TooManyTurns { name, .. }) => {
                    assert!(angles.iter().any(|&u| A::UNKNOWNS[u] == name), "{path}: {name}");
                }
                other => panic!("{path}: {:?}", other.map(|k| k.q)),
            }
        }
        for (path, r) in [
            ("closed form", a.kinematics_flat(&[0.7], &far(1e5), &cfg)),
            ("Newton", b.kinematics_flat(&[0.7], &far(1e5), &cfg)),
        ] {
            let q = r.unwrap_or_else(|e| panic!("{path}: {e}")).q;
            for &u in angles {
                assert_close!(q[u], far(1e5)[u], 1e-6, "{path}: {q:?}");
            }
        }
    }
    check(&FourBar::default(), &FourBarNewton::default(), &[0, 1]);
    // The angle in the block's second column, after the slide.
    check(&SlottedRocker::default(), &SlottedRockerNewton::default(), &[1]);
}

/// Where the links cannot reach, the closed form reports the typed `NoAssembly` with the block
/// and the input, like Newton.
#[test]
fn unreachable_positions_are_no_assembly() {
    // Crank longer than the rod's reach of the slide: sin(psi) = (r sin(phi) - e) / l > 1.
    let m = SliderCrank { r: 4.0, l: 1.0, e: 0.0 };
    let e = m.solve(PI / 2.0).unwrap_err();
    assert!(matches!(e, Error::NoAssembly { .. }), "{e}");
    let msg = e.to_string();
    assert!(msg.contains("phi = 1.57") && msg.contains("block 0"), "{msg}");
    let n = SliderCrankNewton { r: 4.0, l: 1.0, e: 0.0 };
    assert!(matches!(n.solve(PI / 2.0), Err(Error::NoAssembly { .. })));
    // A four-bar whose frame is longer than the other three links together.
    let f = FourBar { a: 1.0, b: 1.0, c: 1.0, d: 5.0, ..FourBar::default() };
    assert!(matches!(f.solve(0.0), Err(Error::NoAssembly { .. })));
    // A non-finite parameter is still named as such.
    let bad = FourBar { c: f64::NAN, ..FourBar::default() };
    assert!(matches!(bad.solve(0.0), Err(Error::NonFinite { ref name, .. }) if name == "c"));
    // A non-finite guess too (the closed form reads it for the branch and the turn).
    let nan = FourBarUnknowns { beta: f64::NAN, gamma: 1.0 };
    let e = FourBar::default().position(0.3, &nan).unwrap_err();
    assert!(matches!(e, Error::NonFinite { what: kinloop::Quantity::Guess, ref name, .. } if name == "beta"), "{e}");
    let e = FourBar::default().kinematics(0.3, &nan).unwrap_err();
    assert!(matches!(e, Error::NonFinite { what: kinloop::Quantity::Guess, ref name, .. } if name == "beta"), "{e}");
}

/// A slider-crank designed to touch its limit (`r - e = l`: at `phi = pi / 2` the rod stands
/// vertical) assembles there in every unit: in metres `0.1 + 0.2` rounds past `0.3`, so the
/// closed form's discriminant is negative by rounding, in millimetres `100 + 200 = 300` exactly.
/// Both give the limit position (the rod at `pi / 2`, its two roots met) and, for the analogs,
/// the singular position, as Newton reports it; a rod short by 1e-9 of its reach is still no
/// assembly.
#[test]
fn a_limit_position_is_the_same_in_every_unit() {
    for scale in [1.0, 1e3, 1e-3, 1e6] {
        let m = SliderCrank { r: 0.1 * scale, l: 0.3 * scale, e: -0.2 * scale };
        let guess = SliderCrankUnknowns { psi: 1.5, x: 0.0 };
        let (q, _) = m.position(PI / 2.0, &guess).unwrap_or_else(|e| panic!("scale {scale}: {e}"));
        assert_close!(q.psi, PI / 2.0, <= 4.0 * f64::EPSILON, "scale {scale}: {}", q.psi);
        assert_close!(q.x, 0.0, <= 1e-15 * scale, "scale {scale}: {}", q.x);
        let e = m.kinematics(PI / 2.0, &guess).unwrap_err();
        assert!(matches!(e, Error::Singular { .. }), "scale {scale}: {e}");
        let n = SliderCrankNewton { r: m.r, l: m.l, e: m.e };
        let newton_guess = SliderCrankNewtonUnknowns { psi: 1.5, x: 0.0 };
        assert!(matches!(n.kinematics(PI / 2.0, &newton_guess), Err(Error::Singular { .. })), "scale {scale}");
        let short = SliderCrank { l: m.l * (1.0 - 1e-9), ..m };
        let e = short.position(PI / 2.0, &guess).unwrap_err();
        assert!(matches!(e, Error::NoAssembly { .. }), "scale {scale}: {e}");
    }
}

/// Scale-free: the same four-bar in millimetres and micrometres gives the same angles.
#[test]
fn closed_forms_are_scale_free() {
    let m = FourBar::default();
    for scale in [1e-6, 1e-3, 1e3] {
        let s = FourBar { a: m.a * scale, b: m.b * scale, c: m.c * scale, d: m.d * scale, pc: m.pc * scale, ..m };
        for k in 0..36 {
            let phi = k as f64 * TAU / 36.0;
            let (x, y) = (m.solve(phi).unwrap(), s.solve(phi).unwrap());
            assert_close!(x.q.beta, y.q.beta, tol::ULPS * x.q.beta.abs().max(1.0), "{scale} {phi}");
            assert_close!(x.q.gamma, y.q.gamma, tol::ULPS * x.q.gamma.abs().max(1.0), "{scale} {phi}");
        }
    }
}

/// Where the two circles of a dyad coincide (the five-bar's crank joints B and D at the same
/// point, links `b = c`), every angle closes the loop (`phi3 = phi2`, any `phi2`): the position
/// is not determined, and the closed form reports the same typed `Singular` error as Newton,
/// for the same block, from any guess (not `NoAssembly`: the loop does close). Coaxial cranks
/// (`d = 0`) of equal length at equal angles make the joints coincide exactly in floating point.
#[test]
fn coincident_joints_are_singular_through_the_closed_form_and_newton() {
    let (a, b, d) = (1.0, 2.0, 0.0);
    let closed = FiveBar { a, b, c: b, d, e: a };
    let newton = FiveBarNewton { a, b, c: b, d, e: a };
    let block = |e: &Error| match e {
        Error::Singular { pivot_ratio, at, .. } => {
            assert!(*pivot_ratio < 1e-8, "{e}");
            at.block.as_ref().map(|(k, _)| *k)
        }
        _ => panic!("not a singular position: {e}"),
    };
    for th in [0.7, -2.0, 3.0] {
        let x = [th, th];
        for guess in [[1.0, 2.0], [0.3, 0.3], [th + 0.2, th - 2.5]] {
            let at = format!("th = {th}, guess {guess:?}");
            let cfg = NewtonConfig::default();
            let ec = closed.kinematics_flat(&x, &guess, &cfg).unwrap_err();
            let en = newton.kinematics_flat(&x, &guess, &cfg).unwrap_err();
            assert_eq!(block(&ec), Some(0), "closed form {at}: {ec}");
            assert_eq!(block(&en), Some(0), "Newton {at}: {en}");
            // Positions alone: Newton's position solve accepts a guess that already closes the
            // loop (`phi2 = phi3`) without factorising; from the others it meets the singularity.
            let ec = closed.position_flat(&x, &guess, &cfg).unwrap_err();
            assert_eq!(block(&ec), Some(0), "closed-form position {at}: {ec}");
            if guess[0] != guess[1] {
                let en = newton.position_flat(&x, &guess, &cfg).unwrap_err();
                assert_eq!(block(&en), Some(0), "Newton position {at}: {en}");
            }
        }
    }
    // Off the coincidence by a hair, the dyad has its two isolated solutions again (whose
    // analogs are ill-conditioned: a singular position too, but one that closes at one angle).
    let near = FiveBar { d: 1e-3, ..closed };
    let k = near.position_flat(&[0.7, 0.7], &[1.0, 2.0], &NewtonConfig::default());
    assert!(k.is_ok(), "{k:?}");
}

/// A four-bar of unit crank, rocker and frame whose coupler is `1e-300` or `1e-20` of them: at a
/// crank angle of `fl(π/3)` the crank pin is `1 - 9.9e-17` from the rocker's pivot (mpmath at
/// 50 digits), so no triangle closes exactly, yet every coupler angle leaves the loop open by at
/// most `5e-17` of its size, far within the residual tolerance: the coupler's angle is not
/// determined, a singular position (positions and analogs alike), in every unit. It was "cannot
/// be assembled", its residual `0`. At `π/3 + 1e-12` the pin is `2 sin(φ/2) - 1 = 8.7e-13` past
/// the rocker's reach, `4.3e-13` of the size: within the default tolerance `1e-12`, singular
/// too; within none of `1e-14`, where it is no assembly by that gap, `(e - 1) / (e + 1)` for `e =
/// 2 sin(φ/2)` (to `1e-3` of it: `e - 1` is known to its rounding, `1e-16` of `8.7e-13`).
#[test]
fn a_coupler_shorter_than_the_tolerance_of_its_loop_is_not_determined() {
    let guess = [0.5, 1.5];
    for scale in [1.0, 1e-3, 1e3] {
        for coupler in [1e-300, 1e-20] {
            let m = kinloop_fixtures::FourBar { a: scale, b: coupler * scale, c: scale, d: scale };
            for phi in [PI / 3.0, PI / 3.0 + 1e-12] {
                let at = format!("scale {scale}, coupler {coupler:e}, phi {phi}");
                let cfg = NewtonConfig::default();
                let errors =
                    [m.kinematics_flat(&[phi], &guess, &cfg).err(), m.position_flat(&[phi], &guess, &cfg).err()];
                for e in errors {
                    match e {
                        Some(e @ Error::Singular { .. }) => {
                            assert_eq!(e.location().and_then(|l| l.block.as_ref()).map(|(k, _)| *k), Some(0), "{at}");
                            assert!(!e.to_string().contains("cannot be assembled"), "{at}: {e}");
                        }
                        other => panic!("{at}: {other:?}"),
                    }
                }
            }
            let phi = PI / 3.0 + 1e-12;
            let strict = NewtonConfig::default().with_residual_tol(1e-14);
            let e = 2.0 * (phi / 2.0).sin();
            let want = (e - 1.0) / (e + 1.0);
            match m.position_flat(&[phi], &guess, &strict) {
                Err(Error::NoAssembly { residual, .. }) => {
                    assert_close!(residual, want, rel = 1e-3, "scale {scale}, coupler {coupler:e}")
                }
                other => panic!("scale {scale}, coupler {coupler:e}: {other:?}"),
            }
        }
    }
}

/// The four-bar of the test above solved by Newton (its twin): the coupler's angle is not
/// determined (every angle closes the loop within `b`, `1e-20` of the size or less, where the
/// tolerance is `1e-12`), and the closed form's verdict is the singular position of block 0. The
/// Newton twin converged on the rocker's angle, then its final correction, through a pivot ratio
/// of about `b / size`, carried the coupler's angle to `4.7e283` rad (`b = 1e-300`) or `-1.2e8`
/// rad (`b = 1e-20` at `π/3 + 1e-12`), beyond the largest angle resolved to the tolerance
/// (`4.5e6` rad), and returned it as the solution. It is now the same singular position, in
/// every unit.
#[test]
fn a_newton_coupler_shorter_than_the_tolerance_is_not_carried_past_every_turn() {
    let guess = [0.5, 1.5];
    let cases = [(1e-300, PI / 3.0), (1e-300, PI / 3.0 + 1e-12), (1e-20, PI / 3.0 + 1e-12), (1e-20, PI / 3.0)];
    for scale in [1.0, 1e-3, 1e3] {
        for (coupler, phi) in cases {
            let at = format!("scale {scale}, coupler {coupler:e}, phi {phi}");
            let m = FourBarNewton { a: scale, b: coupler * scale, c: scale, d: scale, pc: 1.4 * scale, pa: 0.5 };
            let closed = FourBar { a: scale, b: coupler * scale, c: scale, d: scale, pc: 1.4 * scale, pa: 0.5 };
            let cfg = NewtonConfig::default();
            assert!(matches!(closed.position_flat(&[phi], &guess, &cfg), Err(Error::Singular { .. })), "{at}");
            let results = [
                m.position_flat(&[phi], &guess, &cfg).map(|(q, _)| q),
                m.kinematics_flat(&[phi], &guess, &cfg).map(|k| k.q),
            ];
            for r in results {
                assert_singular_block_0(r, &at);
            }
        }
    }
}

/// The largest miss, over `samples` angles of the coupler `b`, of the loop of the four-bar
/// `[a, b, c, d]` at the input `phi` with the rocker at `gamma`, relative to the loop's size
/// `a + b + c + d`: computed here in plain f64 from the loop `a @ phi + b @ beta == (d, 0) + c
/// @ gamma`, independent of the solver.
fn worst_miss_over_coupler_angles([a, b, c, d]: [f64; 4], phi: f64, gamma: f64, samples: usize) -> f64 {
    let miss = |beta: f64| {
        let x = a * phi.cos() + b * beta.cos() - d - c * gamma.cos();
        let y = a * phi.sin() + b * beta.sin() - c * gamma.sin();
        x.hypot(y)
    };
    (0..samples).map(|k| miss(TAU * k as f64 / samples as f64)).fold(0.0, f64::max) / (a + b + c + d)
}

/// The Newton twin's coupler of `1e-20` at `fl(π/3)`, where the crank pin lies within rounding
/// of the rocker's reach: with the rocker along the pivot-to-pin direction, every coupler angle
/// closes the loop within `4 eps` of its size (plain f64, over 64 coupler angles), far within
/// the tolerance `1e-12`, so the coupler's angle is not determined. Newton converged on the
/// rocker and carried the coupler's angle to an arbitrary `-5468` rad (`-38494` at size `1e-3`),
/// which it returned as the solution, position and analogs, where the closed form reports the
/// singular position of block 0. It is now that singular position, from guesses on either side.
#[test]
fn a_newton_coupler_that_every_angle_closes_is_singular_where_it_moved_turns_away() {
    let phi = PI / 3.0;
    for scale in [1.0, 1e-3, 1e3] {
        let links = [scale, 1e-20 * scale, scale, scale];
        // The rocker from its pivot to the crank pin, which the coupler cannot move off.
        let gamma = phi.sin().atan2(phi.cos() - 1.0);
        let worst = worst_miss_over_coupler_angles(links, phi, gamma, 64);
        assert!(worst <= 4.0 * f64::EPSILON, "scale {scale}: every coupler angle misses by {worst:e} at most");
        let [a, b, c, d] = links;
        let m = FourBarNewton { a, b, c, d, pc: 1.4 * scale, pa: 0.5 };
        let cfg = NewtonConfig::default();
        for guess in [[0.5, 1.5], [-2.0, 2.5]] {
            let at = format!("scale {scale}, guess {guess:?}");
            let results = [
                m.position_flat(&[phi], &guess, &cfg).map(|(q, _)| q),
                m.kinematics_flat(&[phi], &guess, &cfg).map(|k| k.q),
            ];
            for r in results {
                assert_singular_block_0(r, &at);
            }
        }
    }
}

/// Towards a limit position of its input, where its Jacobian becomes singular, the Newton twin
/// (whose later evaluations rotate their sines and cosines: `NearTrig`) succeeds wherever the
/// closed form does, down to pivot ratios below 1e-7 (no decision of the iteration flips to a
/// singular block for a few units in the last place more), and agrees with it to the rounding
/// the position amplifies, `16 eps / p` for the smallest pivot ratio `p`, while `p >= 1e-3`.
/// Nearer the limit Newton stops on its residual tolerance, not on rounding (positions then
/// differ by up to about `1e-12 / p²`, with libm's sines as with rotated ones: measured), which
/// the closed form does not have. A non-Grashof four-bar: its input stops where the coupler and
/// the rocker align, `|A - D| = b + c`.
#[test]
fn newton_towards_a_limit_position_agrees_with_the_closed_form() {
    let (a, b, c, d) = (2.6, 1.0, 1.5, 3.2);
    let closed = FourBar { a, b, c, d, ..FourBar::default() };
    let newton = FourBarNewton { a, b, c, d, ..FourBarNewton::default() };
    let limit = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
    let cfg = NewtonConfig::default();
    let start = closed.kinematics_flat(&[limit - 0.3], &[0.3, 1.2], &cfg).unwrap();
    let (mut gc, mut gn) = (start.q, start.q);
    let mut smallest = f64::INFINITY;
    for k in 1..=56 {
        let x = [limit - 0.3 * 0.5f64.powi(k)];
        let kc = closed.kinematics_flat(&x, &gc, &cfg).unwrap_or_else(|e| panic!("closed form at {x:?}: {e}"));
        let kn = newton.kinematics_flat(&x, &gn, &cfg).unwrap_or_else(|e| panic!("Newton at {x:?}: {e}"));
        let p = kc.health.min_pivot;
        if p >= 1e-3 {
            for u in 0..2 {
                let tol = 16.0 * f64::EPSILON / p;
                assert_close!(kc.q[u], kn.q[u], <= tol, "q[{u}] at {x:?} (pivot ratio {p:e})");
            }
        }
        smallest = smallest.min(p);
        (gc, gn) = (kc.q, kn.q);
    }
    assert!(smallest < 1e-7, "the walk must reach the limit's neighbourhood: smallest pivot ratio {smallest:e}");
}

/// The largest miss, over `samples` angles of the rocker `c`, of the loop of the four-bar
/// `[a, b, c, d]` at the input `phi` with the coupler at `beta`, relative to the dyad's size
/// `b + c + |e|` (`e` from the rocker's pivot to the crank pin): computed here in plain f64 from
/// the loop `a @ phi + b @ beta == (d, 0) + c @ gamma`, independent of the solver.
fn worst_miss_over_rocker_angles([a, b, c, d]: [f64; 4], phi: f64, beta: f64, samples: usize) -> f64 {
    let e = (a * phi.cos() - d).hypot(a * phi.sin());
    let size = b + c + e;
    let miss = |gamma: f64| {
        let x = a * phi.cos() + b * beta.cos() - d - c * gamma.cos();
        let y = a * phi.sin() + b * beta.sin() - c * gamma.sin();
        x.hypot(y)
    };
    (0..samples).map(|k| miss(TAU * k as f64 / samples as f64)).fold(0.0, f64::max) / size
}

/// A four-bar of unit crank and coupler whose rocker, the dyad's SECOND link, is `1e-20` or
/// `1e-100` of them, at the input where the coupler's end sits on the rocker's pivot: exactly
/// (frame 2, crank angle 0: the pin at `(1, 0)`, the pivot at `(2, 0)`, coupler along the frame)
/// or within rounding (frame 1, `fl(π/3)`: the pin `1 - 9.9e-17` from the pivot). Every angle
/// of the rocker then closes the loop to within `4 eps` of its size (computed in the test from
/// the coupler's angle in plain f64, over 64 rocker angles), far within the tolerance: the
/// rocker's angle is not determined, a singular position as for a short first link, in every
/// unit. The point solve returned a position with the rocker's angle taken from rounding noise.
#[test]
fn a_rocker_shorter_than_the_rounding_of_its_loop_is_not_determined() {
    let guess = [0.5, 1.5];
    for scale in [1.0, 1e-3, 1e3] {
        for rocker in [1e-20, 1e-100] {
            for (frame, phi) in [(2.0, 0.0), (1.0, PI / 3.0)] {
                let at = format!("scale {scale}, rocker {rocker:e}, frame {frame}, phi {phi}");
                let links = [scale, scale, rocker * scale, frame * scale];
                // The coupler from the pin to the rocker's pivot.
                let beta = (-phi.sin()).atan2(frame - phi.cos());
                let worst = worst_miss_over_rocker_angles(links, phi, beta, 64);
                assert!(worst <= 4.0 * f64::EPSILON, "{at}: every rocker angle misses by {worst:e} at most");
                let [a, b, c, d] = links;
                let m = kinloop_fixtures::FourBar { a, b, c, d };
                let cfg = NewtonConfig::default();
                let results = [
                    m.kinematics_flat(&[phi], &guess, &cfg).map(|k| k.q),
                    m.position_flat(&[phi], &guess, &cfg).map(|(q, _)| q),
                ];
                for r in results {
                    assert_singular_block_0(r, &at);
                }
            }
        }
    }
}
