//! The class IV mechanism of paper 003 (one coupled block of four unknowns): a hand-written
//! Newton for that block, with the same tolerance, warm start and outputs as kinloop (whose
//! variants are in [`crate::kinloop_variants`]).

use crate::decls::ClassFour;
use crate::linalg::{Lu, max_abs};
use crate::rhombic::{MAX_ITERATIONS, TOL};
use crate::sweep::{Failed, Step, Stepper};
// The same cache the generated Newton blocks use (from the expanded code's support module).
use kinloop::__gen::NearTrig;

/// Parameters of the mechanism (the declaration's defaults).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// Crank OA.
    pub oa: f64,
    /// x of the frame pivot B.
    pub xb: f64,
    /// y of the frame pivot B.
    pub yb: f64,
    /// Side AC of the ternary link C-A-E.
    pub ac: f64,
    /// Side AE of the ternary link C-A-E.
    pub ae: f64,
    /// Angle from AC to AE (radians).
    pub alpha_a: f64,
    /// Side BD of the ternary link D-B-F.
    pub bd: f64,
    /// Side BF of the ternary link D-B-F.
    pub bf: f64,
    /// Angle from BD to BF (radians).
    pub alpha_b: f64,
    /// Binary link CD.
    pub cd: f64,
    /// Binary link EF.
    pub ef: f64,
}

/// oa=1.0, xb=4.4, yb=0.6, ac=2.3, ae=2.4, alpha_a=0.84, bd=1.6, bf=3.5, alpha_b=0.62, cd=2.0,
/// ef=3.4.
pub const PARAMS: Params = Params {
    oa: 1.0,
    xb: 4.4,
    yb: 0.6,
    ac: 2.3,
    ae: 2.4,
    alpha_a: 0.84,
    bd: 1.6,
    bf: 3.5,
    alpha_b: 0.62,
    cd: 2.0,
    ef: 3.4,
};

/// The declared assembly mode `th1, th2, psi1, psi2` (a guess at `phi = 0`).
pub const INITIAL_GUESS: [f64; 4] = [1.4, 3.0, -0.8, -1.0];

impl Params {
    /// The kinloop mechanism with these dimensions.
    pub fn kinloop(&self) -> ClassFour {
        ClassFour {
            oa: self.oa,
            xb: self.xb,
            yb: self.yb,
            ac: self.ac,
            ae: self.ae,
            alpha_a: self.alpha_a,
            bd: self.bd,
            bf: self.bf,
            alpha_b: self.alpha_b,
            cd: self.cd,
            ef: self.ef,
        }
    }
}

/// The block written by hand: residuals and Jacobian from shared sines and cosines, a 4x4 LU
/// with partial pivoting per iteration, and at the root one LU shared by the velocity analogs
/// (`J q' = -df/dphi`) and the acceleration analogs (`J q'' = -D2f[(q', 1), (q', 1)]`, each
/// polar term `l @ theta` contributing `-l theta'^2 (cos theta, sin theta)`).
#[derive(Clone, Copy, Debug)]
pub struct HandNewton {
    /// The mechanism's dimensions.
    pub p: Params,
}

/// Sines and cosines of the block's angles at one iterate.
#[derive(Clone, Copy)]
struct Trig {
    s1: f64,
    c1: f64,
    s1a: f64,
    c1a: f64,
    s2: f64,
    c2: f64,
    s2b: f64,
    c2b: f64,
    sp1: f64,
    cp1: f64,
    sp2: f64,
    cp2: f64,
}

impl Stepper<4> for HandNewton {
    #[inline(always)]
    fn step(&self, phi: f64, guess: &[f64; 4]) -> Result<Step<4>, Failed> {
        hand_newton::<false>(&self.p, phi, guess)
    }
}

/// [`HandNewton`] with each iterate's sines and cosines rotated from the previous iterate's,
/// by the runtime's `NearTrig` (what kinloop's generated Newton blocks do): the hand-written
/// reference given the same trigonometry as kinloop.
#[derive(Clone, Copy, Debug)]
pub struct HandNewtonNear {
    /// The mechanism's dimensions.
    pub p: Params,
}

impl Stepper<4> for HandNewtonNear {
    #[inline(always)]
    fn step(&self, phi: f64, guess: &[f64; 4]) -> Result<Step<4>, Failed> {
        hand_newton::<true>(&self.p, phi, guess)
    }
}

/// The hand-written Newton of [`HandNewton`] (with `NEAR`, of [`HandNewtonNear`]).
#[inline(always)]
fn hand_newton<const NEAR: bool>(p: &Params, phi: f64, guess: &[f64; 4]) -> Result<Step<4>, Failed> {
        let (sph, cph) = phi.sin_cos();
        let (ax, ay) = (p.oa * cph, p.oa * sph);
        // With `NEAR`, each iterate's sines and cosines are rotated from the previous
        // iterate's where the angle moved little (the runtime's `NearTrig`, as kinloop's
        // Newton blocks do); otherwise all from libm.
        let near = NearTrig::<6>::new();
        let sin_cos = |slot: usize, arg: f64| if NEAR { near.sin_cos(slot, arg) } else { arg.sin_cos() };
        let eval = |z: &[f64; 4]| {
            let [th1, th2, psi1, psi2] = *z;
            let (s1, c1) = sin_cos(0, th1);
            let (s1a, c1a) = sin_cos(1, th1 + p.alpha_a);
            let (s2, c2) = sin_cos(2, th2);
            let (s2b, c2b) = sin_cos(3, th2 + p.alpha_b);
            let (sp1, cp1) = sin_cos(4, psi1);
            let (sp2, cp2) = sin_cos(5, psi2);
            let f = [
                ax + p.ac * c1 + p.cd * cp1 - p.xb - p.bd * c2,
                ay + p.ac * s1 + p.cd * sp1 - p.yb - p.bd * s2,
                ax + p.ae * c1a + p.ef * cp2 - p.xb - p.bf * c2b,
                ay + p.ae * s1a + p.ef * sp2 - p.yb - p.bf * s2b,
            ];
            (f, Trig { s1, c1, s1a, c1a, s2, c2, s2b, c2b, sp1, cp1, sp2, cp2 })
        };
        let jacobian = |t: &Trig| {
            [
                [-p.ac * t.s1, p.bd * t.s2, -p.cd * t.sp1, 0.0],
                [p.ac * t.c1, -p.bd * t.c2, p.cd * t.cp1, 0.0],
                [-p.ae * t.s1a, p.bf * t.s2b, 0.0, -p.ef * t.sp2],
                [p.ae * t.c1a, -p.bf * t.c2b, 0.0, p.ef * t.cp2],
            ]
        };
        let mut z = *guess;
        let mut iterations = 0;
        let (t, lu) = loop {
            let (f, t) = eval(&z);
            let res = max_abs(&f);
            let lu = Lu::factor(jacobian(&t)).ok_or_else(|| Failed::new("hand Newton: singular block"))?;
            if res <= TOL {
                break (t, lu);
            }
            if !res.is_finite() || iterations >= MAX_ITERATIONS {
                return Err(Failed::new("hand Newton: no convergence"));
            }
            let dz = lu.solve(f.map(|v| -v));
            for u in 0..4 {
                z[u] += dz[u];
            }
            iterations += 1;
        };
        // Velocity analogs: df/dphi = (-oa sin phi, oa cos phi) in both loops.
        let dq = lu.solve([ay, -ax, ay, -ax]);
        let [w1, w2, v1, v2] = dq;
        let (w1, w2, v1, v2) = (w1 * w1, w2 * w2, v1 * v1, v2 * v2);
        let second = [
            -ax - p.ac * t.c1 * w1 - p.cd * t.cp1 * v1 + p.bd * t.c2 * w2,
            -ay - p.ac * t.s1 * w1 - p.cd * t.sp1 * v1 + p.bd * t.s2 * w2,
            -ax - p.ae * t.c1a * w1 - p.ef * t.cp2 * v2 + p.bf * t.c2b * w2,
            -ay - p.ae * t.s1a * w1 - p.ef * t.sp2 * v2 + p.bf * t.s2b * w2,
        ];
        let d2q = lu.solve(second.map(|v| -v));
        Ok(Step { q: z, dq, d2q, iterations })
}
