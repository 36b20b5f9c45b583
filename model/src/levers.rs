//! The tests a position-only solve makes before a closed-form block's solve (the emitter's
//! `lever_checks`, in the compiled mechanism's `position_flat`): with no analogs after it, whose
//! pivot ratio would report a position the data do not determine, the solve tests for one
//! itself. An angle's lever vector (the length of the angle's Jacobian column) against its lever
//! floor, when it has one; a dyad's centres against its longer link.

use crate::tape::{Builder, Segment, Unavailable};
use kinloop_codegen::graph::dag::{Leaf, NodeId, Op};
use kinloop_codegen::plan::Plan;
use kinloop_codegen::plan::closed_form::ClosedForm;
use kinloop_codegen::plan::solve::Solve;
use kinloop_runtime::NewtonConfig;
use kinloop_runtime::generated::{BlockFailure, check_centres, check_guess, check_lever};

/// A closed-form block's position-only tests.
#[derive(Clone, Debug)]
pub(crate) struct Levers {
    /// Computes every register the tests read beyond the block's coefficients, from what the
    /// earlier blocks' solves wrote.
    seg: Segment,
    /// The guesses of a form with a length or slider (its angle, then the other), whose sum
    /// the solve checks first (`check_guess`), as the compiled solve does before its levers.
    guess: Option<[usize; 2]>,
    /// Per angle with a lever floor: the lever's registers and the floors' (one is the floor
    /// itself, several their largest magnitude).
    levers: Vec<([u32; 2], Vec<u32>)>,
    /// A dyad's centres' offset and its two links' vectors.
    centres: Option<([u32; 2], [[u32; 2]; 2])>,
}

impl Levers {
    /// The tests of block `b` of `plan`, `None` for a block that is not a closed form.
    pub(crate) fn build(plan: &Plan, b: usize) -> Result<Option<Levers>, Unavailable> {
        let bp = &plan.blocks[b];
        let Solve::ClosedForm(rec) = &bp.solve else { return Ok(None) };
        let g = &plan.graph;
        let floors = |u: usize| -> Option<Vec<u32>> {
            let c = bp.unknowns.iter().position(|&v| v == u)?;
            (!bp.lever_floor[c].is_empty()).then(|| bp.lever_floor[c].iter().map(|n| n.0).collect())
        };
        // A form with a length or slider has its guesses' sum checked first.
        let guess = match &rec.form {
            ClosedForm::PolarLength { angle, length, .. } => Some([*angle, *length]),
            ClosedForm::AngleSlider { angle, slider, .. } => Some([*angle, *slider]),
            ClosedForm::AngleEquation { .. } | ClosedForm::Dyad { .. } => None,
        };
        let levers: Vec<([u32; 2], Vec<u32>)> =
            rec.form.levers().into_iter().filter_map(|(u, [x, y])| floors(u).map(|f| ([x.0, y.0], f))).collect();
        let centres = rec.form.centres().map(|(e, links)| ([e[0].0, e[1].0], links.map(|[x, y]| [x.0, y.0])));
        let mut roots: Vec<NodeId> = levers.iter().flat_map(|(l, f)| l.iter().chain(f)).map(|&r| NodeId(r)).collect();
        if let Some((e, links)) = &centres {
            roots.extend(e.iter().chain(links.iter().flatten()).map(|&r| NodeId(r)));
        }
        // What the earlier blocks' solves wrote: their unknowns, and a closed form's sines and
        // cosines (its own values, not libm's of its angle); and the block's coefficients. The
        // rest is computed here with the operations of the step's own segments, so the same
        // values.
        let mut tape = Builder::new(g);
        for earlier in &plan.blocks[..b] {
            tape.provide(earlier.unknowns.iter().filter_map(|&u| g.find(Op::Leaf(Leaf::Unknown(u as u16)))));
            if let Solve::ClosedForm(r) = &earlier.solve {
                tape.provide(r.sin_cos.concat());
            }
        }
        // The tests run after the block's own segment, which computed its coefficients.
        tape.provide(rec.form.coefficients());
        let seg = tape.segment(&roots, None)?;
        Ok(Some(Levers { seg, guess, levers, centres }))
    }

    /// The tests, on the registers `r` (the earlier blocks solved, the block's coefficients
    /// computed) from `guess`.
    pub(crate) fn check(&self, r: &mut [f64], guess: &[f64], cfg: &NewtonConfig) -> Result<(), BlockFailure> {
        self.seg.run(r);
        if let Some([a, o]) = self.guess {
            check_guess(guess[a] + guess[o])?;
        }
        for ([x, y], floors) in &self.levers {
            let floor = match floors[..] {
                [one] => r[one as usize],
                _ => crate::factor::max_abs(floors.iter().map(|&f| r[f as usize])),
            };
            check_lever(r[*x as usize], r[*y as usize], floor, cfg)?;
        }
        if let Some(([e0, e1], links)) = &self.centres {
            let sq = |[x, y]: [u32; 2]| {
                let (x, y) = (r[x as usize], r[y as usize]);
                x * x + y * y
            };
            check_centres(r[*e0 as usize], r[*e1 as usize], sq(links[0]), sq(links[1]), cfg)?;
        }
        Ok(())
    }
}
