//! Sines and cosines of one argument paired across scopes, run-time model against compiled code.
//!
//! The macro's schedule computes a sine and the cosine of the same argument together (one
//! `sin_cos`) in the earlier of the two scopes that need them, and every later scope reads that
//! pair. Where that scope is a Newton block's evaluation, the pair comes from the solve's
//! rotation cache (`NearTrig`: the guess's values libm's, later ones rotated, a few units in the
//! last place off libm's), and the outputs, analogs and later blocks read the rotated values of
//! the evaluation the solve returned; in a sweep's kernel an argument free of the unknowns is
//! asked of the sweep's cache (`Rotating`; a sum `phi + gamma` by angle addition from `phi`'s
//! pair and `gamma`'s, in every generated function; [`NestedSums`] holds sums within sums). The
//! declarations below put each half of a pair in a different scope ([`TwoStageNewton`]):
//!
//! * `sin(psi)` only in block 0's equation, `cos(psi)` only in block 1's equation and in an
//!   output: block 0's evaluation computes both (its Jacobian needs the cosine), block 1 and the
//!   output read them from it;
//! * `cos(s)` only in block 1's equation, `sin(s)` only in an output: the same, the other way
//!   round;
//! * `sin(phi)` of the input only in block 0's equation, `cos(phi)` only in the analogs and an
//!   output: one `sin_cos` before block 0;
//! * `sin(phi + gamma)` only in block 1's equation, `cos(phi + gamma)` only in an output: one
//!   pair before block 1, from `phi`'s pair and `gamma`'s by angle addition (`add_angles`).
//!
//! [`TwoStage`] swaps `phi` and `phi + gamma` (the sum's pair needed first, in block 0: `phi`'s
//! pair moves there too, though neither of its halves is needed before block 1) and solves
//! block 0 by its closed form (the angle from its sine; the sine and cosine of `psi` from the
//! equation, no `sin_cos`). That the pairs span those scopes is checked on the expansion itself
//! (`the_expansion_pairs_across_scopes`).
//!
//! A sine or cosine of an argument that depends on a Newton block's unknowns never has its
//! partner only outside the block's evaluation: the Jacobian there needs the partner
//! (`d sin(a) / du = cos(a) da/du`). What crosses the scopes is the reading: later blocks, the
//! analogs and the outputs take the rotated values of the evaluation the solve returned.
//!
//! The reference is the compiled code (straight-line Rust the macro emitted): point steps,
//! positions, steps at a position, sensitivities and the runtime's sweep with libm's input
//! sines must be equal to the last bit, the sweep with the compiled kernel's rotation cache to
//! rounding (a run-time model has no such cache, see `sweeps.rs`).

#[macro_use]
mod common;

use common::{Libm, read};
use kinloop::{Kin, Mechanism, NewtonConfig, Sweep};
use kinloop_model::Model;
use std::f64::consts::TAU;

declared! {
    TWO_STAGE_NEWTON_TEXT =>
    /// A crank `r` at `phi` holds a rod `l` at `psi` to the height `e`; a slide `s` follows
    /// `s - m cos s = k cos psi + r sin(phi + gamma)` (`m < 1`: one root, found by Newton).
    /// Both blocks solved by Newton.
    #[kinloop(newton)]
    #[kinloop(sensitivities)]
    pub struct TwoStageNewton {
        params r = 1.0, l = 3.0, e = 0.4, gamma = 0.3, k = 2.0, m = 0.5;
        input phi;
        unknowns psi = 0.1, s = 2.5;
        eq lift: r * sin(phi) + l * sin(psi) == e;
        eq slide: s - m * cos(s) == k * cos(psi) + r * sin(phi + gamma);
        output reach = r * cos(phi) + l * cos(psi);
        output drop = m * sin(s);
        output lead = cos(phi + gamma);
    }
}

declared! {
    TWO_STAGE_TEXT =>
    /// [`TwoStageNewton`] with the angle sum and the input's own angle swapped (the sum's pair
    /// now needed first), and block 0 by its closed form (an angle from its sine).
    pub struct TwoStage {
        params r = 1.0, l = 3.0, e = 0.4, gamma = 0.3, k = 2.0, m = 0.5;
        input phi;
        unknowns psi = 0.1, s = 2.5;
        eq lift: r * sin(phi + gamma) + l * sin(psi) == e;
        eq slide: s - m * cos(s) == k * cos(psi) + r * sin(phi);
        output reach = r * cos(phi + gamma) + l * cos(psi);
        output drop = m * sin(s);
        output lead = cos(phi);
    }
}

declared! {
    NESTED_SUMS_TEXT =>
    /// Sums of angles within sums: `phi + gamma + delta` by angle addition from
    /// `phi + gamma`'s pair, itself from `phi`'s, each declared before the pair it is computed
    /// from (so the parts' pairs come later in the graph's order and move ahead of it); block 0
    /// by its closed form, block 1 by Newton.
    pub struct NestedSums {
        params r = 1.0, l = 3.0, e = 0.4, gamma = 0.3, delta = 0.2, k = 2.0, m = 0.5;
        input phi;
        unknowns psi = 0.1, s = 2.5;
        eq lift: r * sin(phi + gamma + delta) + l * sin(psi) == e;
        eq slide: s - m * cos(s) == k * cos(psi) + r * sin(phi + gamma);
        output reach = r * cos(phi + gamma + delta) + l * cos(psi);
        output drop = m * sin(s);
        output lead = cos(phi + gamma) + sin(phi) * cos(phi);
    }
}

/// The compiled step kernel (`kinematics_step_sink`: the point step with libm's input sines,
/// the sweep's step with its cache) of `text`'s expansion, without whitespace.
fn step_kernel(text: &str) -> String {
    let code: String = kinloop_codegen::expand(text.parse().expect("tokens")).to_string();
    let code: String = code.chars().filter(|c| !c.is_whitespace()).collect();
    // The expansion names `f64` by its path (a module's own `f64` cannot shadow it); the
    // statements below are written with the short name.
    let code = code.replace("::core::primitive::f64", "f64");
    let from = code.find("fnkinematics_step_sink").expect("a step kernel");
    let to = from + code[from..].find("fnkinematics_flat").expect("followed by kinematics_flat");
    code[from..to].to_string()
}

/// Where `what` is in `code` (the first occurrence), which must hold it.
fn at(code: &str, what: &str) -> usize {
    code.find(what).unwrap_or_else(|| panic!("`{what}` not in the step kernel:\n{code}"))
}

/// `cos(s)` in block 1's equation, `sin(s)` only in the output `drop`: one rotated pair of
/// block 1's evaluation (`m sin s` is its Jacobian's too), the output handed out of it. Returns
/// where block 1 starts.
fn block_1_hands_out_drop(k: &str) -> usize {
    let block1 = at(k, "let__near1=");
    // The guess's evaluation (libm's values, kept in the slot), then the later ones (rotated).
    let seed = at(k, "let(sin_s,cos_s):(f64,f64)=__near1.seed(0,q_s);");
    let drop = at(k, "letout_drop:f64=self.m*sin_s;");
    let rotated = at(k, "let(sin_s,cos_s):(f64,f64)=__near1.sin_cos(0,q_s);");
    let read = at(k, "let[cos_s,sin_s,out_drop,_,_]=__ev1.keep;");
    assert!(block1 < seed && seed < drop && drop < rotated && rotated < read, "{k}");
    block1
}

/// The premise: each pair is one call in the earlier of its two scopes, the later one reads it.
/// Checked on the step kernel (`kinematics_step_sink`, the point step and the sweep's step).
#[test]
fn the_expansion_pairs_across_scopes() {
    for text in [TWO_STAGE_NEWTON_TEXT, TWO_STAGE_TEXT] {
        let k = step_kernel(text);
        assert!(!k.contains(".sin()") && !k.contains(".cos()"), "a sine or cosine not paired\n{k}");
    }
    let k = step_kernel(TWO_STAGE_NEWTON_TEXT);
    let block1 = block_1_hands_out_drop(&k);
    // `sin(psi)` in block 0's equation, `cos(psi)` in its Jacobian: one rotated pair of block 0's
    // evaluation, handed out to block 1 (`k cos psi`, before its solve) and to the output `reach`
    // (`l cos psi`, the Jacobian's entry of the returned evaluation).
    let block0 = at(&k, "let__near0=");
    assert!(block0 < at(&k, "let(sin_psi,cos_psi):(f64,f64)=__near0.sin_cos(0,q_psi);"));
    let (kept, cos_psi) = (at(&k, "let[sin_psi,cos_psi"), at(&k, "self.k*cos_psi"));
    assert!(kept < at(&k, "]=__ev0.keep;") && kept < cos_psi && cos_psi < block1, "{k}");
    assert!(at(&k, "letl_cos_psi:f64=__ev0.j[0][0];") < at(&k, "letout_reach:f64=fx_lift_phi+l_cos_psi;"));
    // The input's pair before block 0 (its sine's scope); its cosine's first use is the analogs'
    // `r cos phi`, after block 1.
    let phi = at(&k, "let(sin_phi,cos_phi):(f64,f64)=__trig.sin_cos(0,x_phi);");
    assert!(phi < block0 && block1 < at(&k, "letfx_lift_phi:f64=self.r*cos_phi;"), "{k}");
    // `phi + gamma`'s pair before block 1 (its sine's scope), its cosine the output `lead`, from
    // `phi`'s pair and `gamma`'s (asked of the cache, which keeps it) by angle addition.
    let gamma = at(&k, "let(sin_gamma,cos_gamma):(f64,f64)=__trig.sin_cos(1,self.gamma);");
    let sum = at(&k, ",out_lead):(f64,f64)=::kinloop::__gen::add_angles((sin_phi,cos_phi),(sin_gamma,cos_gamma));");
    assert!(block0 < gamma && gamma < sum && sum < block1, "{k}");

    let k = step_kernel(TWO_STAGE_TEXT);
    let block1 = block_1_hands_out_drop(&k);
    // The closed form gives `psi`, its sine and its cosine (the angle asked of a sweep's cache);
    // block 1 reads the cosine.
    let block0 = at(&k, "let([q_psi,cos_psi,sin_psi],__check0)");
    assert!(block0 < at(&k, "__trig.angle(0,") && at(&k, "__trig.angle(0,") < at(&k, "self.k*cos_psi"));
    // `sin(phi + gamma)` in block 0, `sin(phi)` only in block 1's equation, `cos(phi)` only in the
    // output `lead`: `phi`'s pair moves before block 0, the sum's from it by angle addition.
    let phi = at(&k, "let(sin_phi,out_lead):(f64,f64)=__trig.sin_cos(0,x_phi);");
    let sum = at(&k, "=::kinloop::__gen::add_angles((sin_phi,out_lead),(sin_gamma,cos_gamma));");
    let sin_phi_use = at(&k, "self.r*sin_phi");
    assert!(phi < sum && sum < block0 && block0 < sin_phi_use && sin_phi_use < block1, "{k}");
}

/// Bits of a slice, for comparisons to the last bit with a readable failure.
fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|v| v.to_bits()).collect()
}

/// Every array of the compiled state `c` and the run-time state `r`, bit for bit.
fn same_bits<const N: usize, const NO: usize>(c: &Kin<N, 1, NO>, r: &kinloop_model::State, what: &str) {
    let f2 = |v: &[[f64; 1]]| v.iter().flatten().copied().collect::<Vec<f64>>();
    let f3 = |v: &[[[f64; 1]; 1]]| v.iter().flatten().flatten().copied().collect::<Vec<f64>>();
    for (name, a, b) in [
        ("q", c.q.to_vec(), &r.q),
        ("dq", f2(&c.dq), &r.dq),
        ("d2q", f3(&c.d2q), &r.d2q),
        ("out", c.out.to_vec(), &r.out),
        ("dout", f2(&c.dout), &r.dout),
        ("d2out", f3(&c.d2out), &r.d2out),
    ] {
        assert_eq!(bits(&a), bits(b), "{what}: {name}, compiled {a:?}, run time {b:?}");
    }
    assert_eq!(c.report.iterations, r.report.iterations, "{what}: iterations");
    assert_eq!(c.health.det_signs, r.health.det_signs, "{what}: determinant signs");
}

/// Point steps over a turn of `phi`, each from the previous position (the sweep's warm start)
/// and from a guess off it by 0.02 rad in `psi` and 0.05 in `s` (more Newton iterations, so
/// more rotations): positions, analogs and outputs bit for bit, the positions-only solve and the
/// step at the solved position too. Returns how many outputs `reach` and `drop` (read out of the
/// Newton evaluations) differ from libm's values at the same positions: the rotated values
/// are in use, a model recomputing them by libm would be caught.
fn point_steps<M: Mechanism<2, 1, 3>>(
    compiled: &M,
    model: &mut Model,
    samples: usize,
    reach: impl Fn(f64, f64) -> f64,
) -> usize {
    let cfg = NewtonConfig::default();
    let m = 0.5;
    let mut q = compiled.guess_flat(&[0.0]);
    let mut not_libm = 0;
    for k in 0..samples {
        let x = [TAU * k as f64 / samples as f64];
        for (g, from) in [(q, "the previous position"), ([q[0] + 0.02, q[1] - 0.05], "a guess off it")] {
            let what = format!("{} at phi = {} from {from}", model.name(), x[0]);
            let c = compiled.kinematics_flat(&x, &g, &cfg).unwrap_or_else(|e| panic!("{what}: {e}"));
            same_bits(&c, model.kinematics(&x, &g, &cfg).unwrap_or_else(|e| panic!("{what}: {e}")), &what);
            let (p, _) = compiled.position_flat(&x, &g, &cfg).expect("positions");
            assert_eq!(bits(&p), bits(model.positions(&x, &g, &cfg).expect("positions")), "{what}: positions");
            let at = compiled.kinematics_at_flat(&x, &c.q, &cfg).expect("at the position");
            same_bits(&at, model.kinematics_at(&x, &c.q, &cfg).expect("at the position"), &format!("{what}, at"));
            let libm = [reach(x[0], c.q[0]), m * c.q[1].sin()];
            not_libm += usize::from(bits(&c.out[..2]) != bits(&libm));
            if from == "the previous position" {
                q = c.q;
            }
        }
    }
    not_libm
}

#[test]
fn point_steps_equal_the_compiled_ones_to_the_bit() {
    let (r, l, gamma) = (1.0, 3.0, 0.3);
    let reach = |phi: f64, psi: f64| r * phi.cos() + l * psi.cos();
    let n = point_steps(&TwoStageNewton::default(), &mut read(TWO_STAGE_NEWTON_TEXT), 360, reach);
    assert!(n > 0, "no output with rotated values");
    eprintln!("two Newton blocks: {n} of 720 steps with outputs other than libm's");
    let reach = |phi: f64, psi: f64| r * (phi + gamma).cos() + l * psi.cos();
    let n = point_steps(&TwoStage::default(), &mut read(TWO_STAGE_TEXT), 360, reach);
    assert!(n > 0, "no output with rotated values");
    eprintln!("closed form then Newton: {n} of 720 steps with outputs other than libm's");
    // Sums within sums, each by angle addition, in the compiled code as in the model.
    let (delta, code) = (0.2, step_kernel(NESTED_SUMS_TEXT));
    assert_eq!(code.matches("add_angles(").count(), 2, "{code}");
    let reach = |phi: f64, psi: f64| r * (phi + gamma + delta).cos() + l * psi.cos();
    point_steps(&NestedSums::default(), &mut read(NESTED_SUMS_TEXT), 360, reach);
}

/// A coupled Newton block of four unknowns (the class IV group, `kinloop_fixtures`): its
/// equations hold `sin` and `cos` of `th1 + alpha_a` and `th2 + alpha_b`, rotated in its
/// evaluation, which hands them (and the output points, partial sums of its equations) to the
/// analogs and the outputs. Point steps over a turn from the
/// previous position and from a guess off it, every array bit for bit.
#[test]
fn a_coupled_block_hands_its_pairs_to_the_outputs_bit_for_bit() {
    use kinloop_fixtures as fx;
    let cfg = NewtonConfig::default();
    let compiled = fx::ClassFour::default();
    let mut model = read(fx::CLASS_FOUR_TEXT);
    let mut q = compiled.guess_flat(&[0.0]);
    for k in 0..180 {
        let x = [TAU * k as f64 / 180.0];
        let off: [f64; 4] = std::array::from_fn(|u| q[u] + if u % 2 == 0 { 2e-3 } else { -3e-3 });
        for (g, from) in [(q, "the previous position"), (off, "a guess off it")] {
            let what = format!("class IV at phi = {} from {from}", x[0]);
            let c = compiled.kinematics_flat(&x, &g, &cfg).unwrap_or_else(|e| panic!("{what}: {e}"));
            same_bits(&c, model.kinematics(&x, &g, &cfg).unwrap_or_else(|e| panic!("{what}: {e}")), &what);
            if from == "the previous position" {
                q = c.q;
            }
        }
    }
}

/// The sensitivities to every parameter (the compiled `sensitivities_flat`, its own solve and
/// its own schedule over the same pairs) over a turn, bit for bit.
#[test]
fn sensitivities_equal_the_compiled_ones_to_the_bit() {
    use kinloop::Sensitivities;
    let cfg = NewtonConfig::default();
    let compiled = TwoStageNewton::default();
    let mut model = read(TWO_STAGE_NEWTON_TEXT);
    let mut q = compiled.guess_flat(&[0.0]);
    for k in 0..90 {
        let x = [TAU * k as f64 / 90.0];
        let (c, cs) = compiled.sensitivities_flat(&x, &q, &cfg).expect("compiled");
        let (r, rs) = model.sensitivities(&x, &q, &cfg).expect("run time");
        same_bits(&c, r, &format!("phi = {}", x[0]));
        let rs = rs.expect("declared with sensitivities");
        for (name, a, b) in [
            ("q", cs.q.iter().flatten().copied().collect::<Vec<f64>>(), &rs.q),
            ("dq", cs.dq.iter().flatten().flatten().copied().collect(), &rs.dq),
            ("d2q", cs.d2q.iter().flatten().flatten().flatten().copied().collect(), &rs.d2q),
            ("out", cs.out.iter().flatten().copied().collect(), &rs.out),
            ("dout", cs.dout.iter().flatten().flatten().copied().collect(), &rs.dout),
            ("d2out", cs.d2out.iter().flatten().flatten().flatten().copied().collect(), &rs.d2out),
        ] {
            assert_eq!(bits(&a), bits(b), "phi = {}: sensitivities of {name}", x[0]);
        }
        q = c.q;
    }
}

/// Relative agreement demanded of the sweep with the compiled rotation cache, of each array's
/// largest magnitude: its few units in the last place, amplified by a step's Newton correction
/// (as `sweeps.rs`).
const REL: f64 = 1e-13;

/// The runtime's sweep over a turn of `phi`, over the compiled kernel `compiled` and over the
/// model; returns the samples compared and the largest relative difference of any array.
fn sweep<M: Mechanism<2, 1, 3>>(compiled: &M, model: &mut Model, samples: usize, exact: bool) -> (usize, f64) {
    let guess = compiled.guess_flat(&[0.0]);
    let mut c = Sweep::<M, Kin<2, 1, 3>, 2, 1, 3>::new(compiled, [0.0], [TAU], samples, guess).expect("sweep");
    let mut r = model.sweep(&[0.0], &[TAU], samples, &guess).expect("sweep");
    let (mut n, mut worst) = (0, 0.0f64);
    while let (Some(a), Some(b)) = (c.next_ref(), r.next_ref()) {
        let (a, b) = (a.expect("compiled sweep"), b.expect("run-time sweep"));
        let f2 = |v: &[[f64; 1]]| v.iter().flatten().copied().collect::<Vec<f64>>();
        let f3 = |v: &[[[f64; 1]; 1]]| v.iter().flatten().flatten().copied().collect::<Vec<f64>>();
        for (x, y) in [
            (a.q.to_vec(), &b.q),
            (f2(&a.dq), &b.dq),
            (f3(&a.d2q), &b.d2q),
            (a.out.to_vec(), &b.out),
            (f2(&a.dout), &b.dout),
            (f3(&a.d2out), &b.d2out),
        ] {
            if exact {
                assert_eq!(bits(&x), bits(y), "sample {n}: compiled {x:?}, run time {y:?}");
            }
            let scale = x.iter().chain(y).fold(0.0f64, |m, v| m.max(v.abs())).max(f64::MIN_POSITIVE);
            worst = x.iter().zip(y).fold(worst, |w, (p, q)| w.max((p - q).abs() / scale));
        }
        n += 1;
    }
    assert!(c.next().is_none() && r.next().is_none(), "the sweeps end together");
    assert!(c.events().is_empty() && r.events().is_empty(), "{:?} {:?}", c.events(), r.events());
    (n, worst)
}

#[test]
fn sweeps_equal_the_compiled_ones() {
    for (name, text) in [("two Newton blocks", TWO_STAGE_NEWTON_TEXT), ("closed form then Newton", TWO_STAGE_TEXT)] {
        let mut model = read(text);
        let (n, w) = if name == "two Newton blocks" {
            let exact = sweep(&Libm(TwoStageNewton::default()), &mut model, 361, true);
            let cached = sweep(&TwoStageNewton::default(), &mut model, 361, false);
            (exact.0.min(cached.0), cached.1)
        } else {
            let exact = sweep(&Libm(TwoStage::default()), &mut model, 361, true);
            let cached = sweep(&TwoStage::default(), &mut model, 361, false);
            (exact.0.min(cached.0), cached.1)
        };
        assert_eq!(n, 361, "{name}: samples compared");
        assert!(w <= REL, "{name}: largest relative difference {w:e} with the rotation cache");
        eprintln!("{name}: {n} samples bit for bit with libm's sines, {w:e} with the rotation cache");
    }
}
