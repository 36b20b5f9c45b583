//! kinloop against independent 50-digit references (tests/reference/generate.py, mpmath): a
//! four-bar with a coupler point, an offset slider-crank, a two-loop Watt six-bar, a class IV
//! group, a rhombic drive, a two-input five-bar, the gear-lever drive and the slotted lever
//! (polar blocks: a length and an angle), two cam linkages (a chain of a dyad and a slider's
//! one-angle block; a dyad moved by an explicit lift law) and the roller edger (a dyad whose link
//! lengthens with the input, time), over a whole crank turn (the edger's stroke), in point solves
//! (from a guess 0.05 rad off) and in sweeps.
//!
//! Tolerances: positions within 1e-14 (angles absolute, lengths relative to the largest link:
//! a few ulps of the loop's magnitude), analogs within 1e-12 relative to the largest magnitude
//! of their column over the turn (the analogs come from one factorisation of a well-conditioned
//! Jacobian: rounding times its condition number, here below 1e2).

use kinloop::{Kin, Mechanism, NewtonConfig};
use kinloop_fixtures::SlottedLever;
use kinloop_fixtures::cam_linkage::{CamLinkage, HarmonicCamRocker};
use kinloop_fixtures::gear_lever::GearLever;
use kinloop_fixtures::roller_edger::RollerEdger;
use std::f64::consts::PI;

kinloop::mechanism! {
    /// Crank-rocker with a coupler point P at `p` from B, `alpha` off the coupler.
    pub struct FourBarP {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2, p = 1.5, alpha = 0.6;
        input phi;
        unknowns beta = 0.5, gamma = 1.5;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        point pp = a @ phi + p @ (beta + alpha);
    }
}

kinloop::mechanism! {
    /// Crank-rocker whose rocker is a twelfth of its coupler: the angle at B between B -> D and
    /// the coupler stays below 3 degrees.
    pub struct ShortRockerFourBar {
        params a = 0.2, b = 3.0, c = 0.25, d = 3.0;
        input phi;
        unknowns beta = 0.05, gamma = 1.0;
        loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
    }
}

kinloop::mechanism! {
    /// Offset slider-crank: crank `r`, rod `l`, slider at height `e`.
    pub struct OffsetSliderCrank {
        params r = 1.0, l = 3.0, e = 0.5;
        input phi;
        unknowns psi = 0.1, x = 3.9;
        loop oab: r @ phi + l @ psi == (x, e);
    }
}

kinloop::mechanism! {
    /// Watt six-bar: the four-bar's rocker is ternary and drives a second four-bar.
    pub struct WattSixBar {
        params a = 1.0, b = 3.0, c = 2.5, d = 3.2, c2 = 2.0, delta = 0.5, e5 = 3.5, f6 = 2.5, gx = 6.0, gy = 1.0;
        input phi;
        unknowns beta = 0.5, gamma = 1.5, th5 = 0.3, th6 = 1.6;
        loop first: a @ phi + b @ beta == (d, 0) + c @ gamma;
        loop second: (d, 0) + c2 @ (gamma + delta) + e5 @ th5 == (gx, gy) + f6 @ th6;
        point g = (d, 0) + c2 @ (gamma + delta) + e5 @ th5;
    }
}

kinloop::mechanism! {
    /// Class IV group: crank OA, ternary links CAE (at A) and DBF (at B), binary links CD, EF.
    pub struct ClassFour {
        params oa = 1.0, xb = 4.4, yb = 0.6, ac = 2.3, ae = 2.4, alpha_a = 0.84,
               bd = 1.6, bf = 3.5, alpha_b = 0.62, cd = 2.0, ef = 3.4;
        input phi;
        unknowns th1 = 1.4, th2 = 3.0, psi1 = -0.8, psi2 = -1.0;
        let a = oa @ phi;
        let b = (xb, yb);
        loop acdb: a + ac @ th1 + cd @ psi1 == b + bd @ th2;
        loop aefb: a + ae @ (th1 + alpha_a) + ef @ psi2 == b + bf @ (th2 + alpha_b);
        point c = a + ac @ th1;
    }
}

kinloop::mechanism! {
    /// Rhombic drive (paper 000), its second crank set `gamma` ahead of the first, declared (with
    /// its unknowns) before it: in a sweep the cache gives `sin(phi1 + gamma)` by angle addition
    /// from `phi1`'s values, which the kernel then computes first.
    pub struct RhombicDrive {
        params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, de = 0.9, gamma = 0.7;
        input phi1;
        unknowns phi4 = pi, x_f = l_b, phi2 = 0, x_c = -l_p;
        loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
        loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
    }
}

/// One reference row: the `NI` inputs, then `q` (N), `dq` (N times NI: by each input), `d2q` (N
/// times the input pairs `(i, j)`, `i <= j`), then the points' columns, their first and second
/// analogs (NO each, laid out alike).
struct Reference {
    rows: Vec<Vec<f64>>,
}

impl Reference {
    fn parse(text: &str) -> Reference {
        let rows = text
            .lines()
            .skip(1)
            .filter(|l| !l.is_empty())
            .map(|l| l.split(',').map(|v| v.parse::<f64>().expect("a number")).collect())
            .collect();
        Reference { rows }
    }

    /// The reference of the mechanism with every length multiplied by `size` (a power of two,
    /// so exactly): the columns of the `quantities` that are lengths (unknowns below `at.n`,
    /// then the point and output columns), their positions and analogs, times `size`.
    fn scaled(&self, size: f64, at: Layout, quantities: &[usize]) -> Reference {
        let mut rows = self.rows.clone();
        for &k in quantities {
            let mut columns = vec![at.position(k)];
            for i in 0..at.ni {
                columns.push(at.first(k, i));
                columns.extend((i..at.ni).map(|j| at.second(k, i, j)));
            }
            for row in &mut rows {
                for &c in &columns {
                    row[c] *= size;
                }
            }
        }
        Reference { rows }
    }

    /// Largest magnitude of column `k` over the turn.
    fn column_max(&self, k: usize) -> f64 {
        self.rows.iter().map(|r| r[k].abs()).fold(0.0, f64::max)
    }
}

/// The columns of a row with `NI` inputs, `N` unknowns and `NO` point columns.
#[derive(Clone, Copy)]
struct Layout {
    ni: usize,
    n: usize,
    no: usize,
}

impl Layout {
    /// Input pairs `(i, j)` with `i <= j`.
    fn pairs(&self) -> usize {
        self.ni * (self.ni + 1) / 2
    }

    /// Index of the pair `(i, j)`, in either order, among `(0, 0), (0, 1), .., (1, 1), ..`.
    fn pair(&self, i: usize, j: usize) -> usize {
        let (i, j) = (i.min(j), i.max(j));
        i * self.ni - i * (i.saturating_sub(1)) / 2 + (j - i)
    }

    /// Columns of the quantity `k` (an unknown below `n`, then the point columns): its position,
    /// its first analog by input `i`, its second by inputs `i`, `j`.
    fn position(&self, k: usize) -> usize {
        if k < self.n { self.ni + k } else { self.ni + self.n * (1 + self.ni + self.pairs()) + (k - self.n) }
    }

    fn first(&self, k: usize, i: usize) -> usize {
        let (count, at) = if k < self.n { (self.n, k) } else { (self.no, k - self.n) };
        self.position(k) - at + count + at * self.ni + i
    }

    fn second(&self, k: usize, i: usize, j: usize) -> usize {
        let (count, at) = if k < self.n { (self.n, k) } else { (self.no, k - self.n) };
        self.position(k) - at + count * (1 + self.ni) + at * self.pairs() + self.pair(i, j)
    }
}

/// The kinds of a reference's quantities: which unknowns are `lengths` (compared relative to
/// `length`), the others angles (absolute); the outputs are lengths but for `angle_outputs`
/// (their indices among the output columns).
#[derive(Clone, Copy)]
struct Kinds<'a> {
    lengths: &'a [usize],
    angle_outputs: &'a [usize],
    length: f64,
}

/// Row `row` of `reference` against `k`, its quantities of `kinds`.
fn compare<const N: usize, const NI: usize, const NO: usize>(
    name: &str,
    reference: &Reference,
    row: usize,
    k: &Kin<N, NI, NO>,
    Kinds { lengths, angle_outputs, length }: Kinds,
) {
    let r = &reference.rows[row];
    let at = Layout { ni: NI, n: N, no: NO };
    let pos = |u: usize, got: f64, want: f64, is_length: bool| {
        let tol = if is_length { 1e-14 * length } else { 1e-14 };
        assert_close!(got, want, <= tol, "{name} row {row}: position {u} {got} vs {want} (tol {tol:e})");
    };
    let analog = |col: usize, got: f64| {
        let tol = 1e-12 * reference.column_max(col);
        assert_close!(got, r[col], <= tol, "{name} row {row}: column {col} {got} vs {} (tol {tol:e})", r[col]);
    };
    for u in 0..N {
        pos(u, k.q[u], r[at.position(u)], lengths.contains(&u));
        for i in 0..NI {
            analog(at.first(u, i), k.dq[u][i]);
            for j in 0..NI {
                analog(at.second(u, i, j), k.d2q[u][i][j]);
            }
        }
    }
    for o in 0..NO {
        pos(N + o, k.out[o], r[at.position(N + o)], !angle_outputs.contains(&o));
        for i in 0..NI {
            analog(at.first(N + o, i), k.dout[o][i]);
            for j in 0..NI {
                analog(at.second(N + o, i, j), k.d2out[o][i][j]);
            }
        }
    }
}

/// The first `NI` columns of `row`: its inputs.
fn inputs<const NI: usize>(row: &[f64]) -> [f64; NI] {
    row[..NI].try_into().expect("a row holds its inputs")
}

/// The unknowns of `row`.
fn unknowns<const N: usize, const NI: usize>(row: &[f64]) -> [f64; N] {
    row[NI..NI + N].try_into().expect("a row holds its unknowns")
}

fn check<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    name: &str,
    m: &M,
    text: &str,
    lengths: &[usize],
    length: f64,
) {
    check_against(name, m, &Reference::parse(text), Kinds { lengths, angle_outputs: &[], length }, 1.0);
}

/// [`check`] against a parsed (or scaled) reference of a mechanism `size` times the
/// reference's.
fn check_against<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    name: &str,
    m: &M,
    reference: &Reference,
    kinds: Kinds,
    size: f64,
) {
    let cfg = NewtonConfig::default();
    // Point solves from a guess 0.05 off in every unknown (times the size in a length).
    for (i, r) in reference.rows.iter().enumerate() {
        let mut guess = unknowns::<N, NI>(r);
        for (u, q) in guess.iter_mut().enumerate() {
            *q += if kinds.lengths.contains(&u) { 0.05 * size } else { 0.05 };
        }
        let k = m.kinematics_flat(&inputs(r), &guess, &cfg).unwrap_or_else(|e| panic!("{name} row {i}: {e}"));
        compare(name, reference, i, &k, kinds);
    }
    // A sweep through the same inputs (its own predictor, its own step control).
    let first = &reference.rows[0];
    let last = &reference.rows[reference.rows.len() - 1];
    let sweep = kinloop::Sweep::<M, Kin<N, NI, NO>, N, NI, NO>::new(
        m,
        inputs(first),
        inputs(last),
        reference.rows.len(),
        unknowns::<N, NI>(first),
    )
    .unwrap();
    for (i, k) in sweep.enumerate() {
        let k = k.unwrap_or_else(|e| panic!("{name} sweep sample {i}: {e}"));
        for (x, want) in k.x.iter().zip(&reference.rows[i]) {
            assert_close!(*x, *want, <= 4.0 * f64::EPSILON * 7.0, "{name} sample {i} at {:?}", k.x);
        }
        compare(name, reference, i, &k, kinds);
    }
    fine_sweep(name, m, reference, kinds);
}

/// Sub-samples per reference row in [`fine_sweep`]: 0.25 degree apart, where a sweep advances
/// the sines and cosines of its inputs by rotation (below 1.8 degrees) instead of libm.
const FINE: usize = 60;

/// A sweep of `FINE` samples per reference row: at the reference rows it matches the reference
/// as the coarse sweep does, and every sample matches a point solve at the same input (libm's
/// sines and cosines) within the same tolerances: the rotated values cost no precision.
fn fine_sweep<M: Mechanism<N, NI, NO>, const N: usize, const NI: usize, const NO: usize>(
    name: &str,
    m: &M,
    reference: &Reference,
    kinds: Kinds,
) {
    let Kinds { lengths, length, .. } = kinds;
    let (first, last) = (&reference.rows[0], &reference.rows[reference.rows.len() - 1]);
    let samples = (reference.rows.len() - 1) * FINE + 1;
    let sweep = kinloop::Sweep::<M, Kin<N, NI, NO>, N, NI, NO>::new(
        m,
        inputs(first),
        inputs(last),
        samples,
        unknowns::<N, NI>(first),
    )
    .unwrap();
    let cfg = NewtonConfig::default();
    let at = Layout { ni: NI, n: N, no: NO };
    let mut worst = [0.0f64; 2];
    for (i, k) in sweep.enumerate() {
        let k = k.unwrap_or_else(|e| panic!("{name} fine sweep sample {i}: {e}"));
        if i % FINE == 0 {
            compare(name, reference, i / FINE, &k, kinds);
        }
        let point = m.kinematics_flat(&k.x, &k.q, &cfg).unwrap_or_else(|e| panic!("{name} point {i}: {e}"));
        for u in 0..N {
            let scale = if lengths.contains(&u) { length } else { 1.0 };
            worst[0] = worst[0].max((k.q[u] - point.q[u]).abs() / scale);
            let columns = (0..NI).flat_map(|i| (0..NI).flat_map(move |j| [at.first(u, i), at.second(u, i, j)]));
            let d_scale = columns.map(|c| reference.column_max(c)).fold(0.0, f64::max);
            for i in 0..NI {
                worst[1] = worst[1].max((k.dq[u][i] - point.dq[u][i]).abs() / d_scale);
                for j in 0..NI {
                    worst[1] = worst[1].max((k.d2q[u][i][j] - point.d2q[u][i][j]).abs() / d_scale);
                }
            }
        }
    }
    assert!(worst[0] <= 1e-14 && worst[1] <= 1e-12, "{name}: fine sweep vs point solves {worst:?}");
}

#[test]
fn four_bar_with_coupler_point_matches_the_50_digit_reference() {
    check("four_bar", &FourBarP::default(), include_str!("../reference/four_bar.csv"), &[], 3.2);
}

/// The dyad's root from its coefficients alone (`a² + b² - c²`) lost digits to cancellation
/// here: the coupler's angle 5 eps off, which the rocker, a twelfth of the coupler, turned into
/// 3e-14 rad; from the triangle of the lengths, rounding alone.
#[test]
fn short_rocker_four_bar_matches_the_50_digit_reference() {
    check(
        "short_rocker_four_bar",
        &ShortRockerFourBar::default(),
        include_str!("../reference/short_rocker_four_bar.csv"),
        &[],
        3.0,
    );
}

/// The same four-bar at sizes where the dyad's `a² + b²` (a fourth power of the lengths) leaves
/// the range of `f64` and its equation is solved divided by a power of two: its angles and
/// their analogs are those of the unit-sized one. There the root came from the coefficients
/// alone, at any angle of the triangle.
#[test]
fn short_rocker_four_bar_at_extreme_sizes_matches_the_50_digit_reference() {
    for size in [2f64.powi(-300), 2f64.powi(300), 2f64.powi(-500), 2f64.powi(500)] {
        let ShortRockerFourBar { a, b, c, d } = ShortRockerFourBar::default();
        let m = ShortRockerFourBar { a: a * size, b: b * size, c: c * size, d: d * size };
        check("short_rocker_four_bar", &m, include_str!("../reference/short_rocker_four_bar.csv"), &[], 3.0 * size);
    }
}

#[test]
fn offset_slider_crank_matches_the_50_digit_reference() {
    check("slider_crank", &OffsetSliderCrank::default(), include_str!("../reference/slider_crank.csv"), &[1], 3.0);
}

#[test]
fn watt_six_bar_matches_the_50_digit_reference() {
    check("watt_six_bar", &WattSixBar::default(), include_str!("../reference/watt_six_bar.csv"), &[], 6.0);
}

#[test]
fn class_four_group_matches_the_50_digit_reference() {
    check("class_four", &ClassFour::default(), include_str!("../reference/class_four.csv"), &[], 4.4);
}

#[test]
fn rhombic_drive_matches_the_50_digit_reference() {
    check("rhombic_drive", &RhombicDrive::default(), include_str!("../reference/rhombic_drive.csv"), &[1, 3], 3.5);
}

kinloop::mechanism! {
    /// Five-bar driven by two cranks (the fixtures' `FiveBar`): crank `a` at the origin
    /// (`th1`), crank `e` at `(d, 0)` (`th2`), links `b` from B and `c` from D meeting at C.
    pub struct FiveBarC {
        params a = 1.0, b = 2.5, c = 2.2, d = 1.5, e = 1.2;
        inputs th1, th2;
        unknowns phi2 = 1.0, phi3 = 2.0;
        loop abcde: a @ th1 + b @ phi2 == (d, 0) + e @ th2 + c @ phi3;
        point pc = a @ th1 + b @ phi2;
    }
}

/// Two inputs: the positions, the first analogs by each crank and the second ones by each pair
/// of cranks, the cross derivatives included (both orders against the reference's one column),
/// along the line `th2 = th1 - pi + 0.3` over a turn.
#[test]
fn five_bar_matches_the_50_digit_reference() {
    check("five_bar", &FiveBarC::default(), include_str!("../reference/five_bar.csv"), &[], 2.5);
}

// The mechanisms below are the fixtures' (the examples' and the papers' tests'), each given here
// the parameters the reference was computed with.

/// A polar block: the pin's distance from the rocker's pivot and the rocker's angle, which turns
/// once a carrier turn with three stops and swings through half a radian between rows where the
/// pin passes nearest the pivot (72 rows a turn).
#[test]
fn gear_lever_matches_the_50_digit_reference() {
    let m = GearLever { l_c: 2.0, l_p: 1.3, u: 3.0 };
    check("gear_lever", &m, include_str!("../reference/gear_lever.csv"), &[0], 3.3);
}

#[test]
fn slotted_lever_matches_the_50_digit_reference() {
    let m = SlottedLever { r: 1.0, d: 2.0, l: 4.0 };
    check("slotted_lever", &m, include_str!("../reference/slotted_lever.csv"), &[0], 4.0);
}

/// Two loops in a chain: the cam pair's dyad, then the slider's one-angle block and its linear
/// length on the rocker's second arm; the pressure angle an output of the unknowns (compared as
/// an angle, absolutely). Millimetres.
#[test]
fn cam_linkage_matches_the_50_digit_reference() {
    let m = CamLinkage {
        e: 10.0,
        r_cam: 40.0,
        r_roller: 12.0,
        a_x: 0.0,
        a_y: 80.0,
        l_arm: 60.0,
        l_out: 50.0,
        delta: 140.0 * PI / 180.0,
        l_rod: 150.0,
        h: 130.0,
    };
    let reference = Reference::parse(include_str!("../reference/cam_linkage.csv"));
    check_against("cam_linkage", &m, &reference, Kinds { lengths: &[3], angle_outputs: &[6], length: 150.0 }, 1.0);
}

/// A dyad whose base point the input moves through an explicit law (its analogs those of the
/// law's derivatives through the chain rule).
#[test]
fn harmonic_cam_rocker_matches_the_50_digit_reference() {
    let m = HarmonicCamRocker { lift: 20.0, y0: 60.0, l_rod: 70.0, c: 40.0, d_x: -40.0, d_y: 140.0 };
    check("harmonic_cam_rocker", &m, include_str!("../reference/harmonic_cam_rocker.csv"), &[], 140.0);
}

/// Time as the input: contour 1 a dyad whose first link (the cylinder) lengthens with it, contour
/// 2 a dyad on contour 1's link 3, over the cylinder's stroke (6 s).
#[test]
fn roller_edger_matches_the_50_digit_reference() {
    let m =
        RollerEdger { l1: 0.9, l3: 0.6, l5: 1.2, alpha: 0.2, v1: 0.05, l2: 1.0, s2: 0.1, l4: 0.7, l6: 1.4, beta: 0.9 };
    check("roller_edger", &m, include_str!("../reference/roller_edger.csv"), &[], 1.4);
}

/// Sizes where the fourth powers of the lengths (`2^±1200`, `2^±2000`), which a dyad's
/// coefficients hold, leave the range of `f64` (its equation is then solved divided by a power of
/// two), and their squares (up to `2^±1000`) come near its ends.
fn extreme_sizes() -> [f64; 4] {
    [2f64.powi(-300), 2f64.powi(300), 2f64.powi(-500), 2f64.powi(500)]
}

/// The polar blocks at extreme sizes: the lengths (the pin's distance, the pin, the tip) scale,
/// the angles are the unit-sized ones'.
#[test]
fn polar_blocks_at_extreme_sizes_match_the_50_digit_reference() {
    for size in extreme_sizes() {
        let m = GearLever { l_c: 2.0 * size, l_p: 1.3 * size, u: 3.0 };
        let reference = Reference::parse(include_str!("../reference/gear_lever.csv"));
        let reference = reference.scaled(size, Layout { ni: 1, n: 2, no: 2 }, &[0, 2, 3]);
        check_against(
            "gear_lever",
            &m,
            &reference,
            Kinds { lengths: &[0], angle_outputs: &[], length: 3.3 * size },
            size,
        );
        let m = SlottedLever { r: size, d: 2.0 * size, l: 4.0 * size };
        let reference = Reference::parse(include_str!("../reference/slotted_lever.csv"));
        let reference = reference.scaled(size, Layout { ni: 1, n: 2, no: 2 }, &[0, 2, 3]);
        check_against(
            "slotted_lever",
            &m,
            &reference,
            Kinds { lengths: &[0], angle_outputs: &[], length: 4.0 * size },
            size,
        );
    }
}

/// The cam linkage's chain (a dyad, then a one-angle block and a linear length) and the cam
/// rocker's dyad moved by its lift law at extreme sizes; the pressure angle does not scale.
#[test]
fn cam_linkages_at_extreme_sizes_match_the_50_digit_reference() {
    for size in extreme_sizes() {
        let m = CamLinkage {
            e: 10.0 * size,
            r_cam: 40.0 * size,
            r_roller: 12.0 * size,
            a_x: 0.0,
            a_y: 80.0 * size,
            l_arm: 60.0 * size,
            l_out: 50.0 * size,
            delta: 140.0 * PI / 180.0,
            l_rod: 150.0 * size,
            h: 130.0 * size,
        };
        let reference = Reference::parse(include_str!("../reference/cam_linkage.csv"));
        let reference = reference.scaled(size, Layout { ni: 1, n: 4, no: 7 }, &[3, 4, 5, 6, 7, 8, 9]);
        check_against(
            "cam_linkage",
            &m,
            &reference,
            Kinds { lengths: &[3], angle_outputs: &[6], length: 150.0 * size },
            size,
        );
        let m = HarmonicCamRocker {
            lift: 20.0 * size,
            y0: 60.0 * size,
            l_rod: 70.0 * size,
            c: 40.0 * size,
            d_x: -40.0 * size,
            d_y: 140.0 * size,
        };
        let reference = Reference::parse(include_str!("../reference/harmonic_cam_rocker.csv"));
        let reference = reference.scaled(size, Layout { ni: 1, n: 2, no: 4 }, &[2, 3, 4, 5]);
        check_against(
            "harmonic_cam_rocker",
            &m,
            &reference,
            Kinds { lengths: &[], angle_outputs: &[], length: 140.0 * size },
            size,
        );
    }
}
