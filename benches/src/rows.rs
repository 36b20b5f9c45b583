//! The three closed-form rows (the rhombic drive, the four-bar with its coupler point, the
//! gear-lever rocker), built once for the criterion benchmark and the report binary: each
//! mechanism as kinloop solves it, its hand closed form, the sweep recipe written by hand and its
//! position at input 0.

use std::hint::black_box;

use kinloop::Mechanism;

use crate::hand::{FOUR_BAR, FourBarClosed, GearLeverClosed, gear_lever};
use crate::hand_sweep::{
    FOUR_BAR_TERMS, FourBarSweep, GEAR_LEVER_TERMS, GearLeverSweep, HandSweep, PERIOD, RHOMBIC_TERMS, RhombicSweep,
};
use crate::rhombic::{self, ClosedForm};
use crate::sweep::Stepper;

/// Steps a turn of the closed-form rows (the criterion groups' and the report's).
pub const TURN_720: usize = 720;

/// What is done with each closed-form row (see [`closed_form_rows`]).
pub trait RowVisitor {
    /// One row: the mechanism `m` as kinloop solves it, its hand closed form `hand`, the sweep
    /// recipe written by hand `sweep` ([`crate::hand_sweep`], at [`TURN_720`] samples a turn),
    /// and the position at input 0; `name` the row's short name (`rhombic`, `four_bar`,
    /// `gear_lever`), `title` its title in the report's tables.
    #[allow(clippy::too_many_arguments)]
    fn row<
        M: Mechanism<N, 1, NO>,
        H: Stepper<N>,
        S: HandSweep<N, NP>,
        const N: usize,
        const NO: usize,
        const NP: usize,
    >(
        &mut self,
        name: &str,
        title: &str,
        m: M,
        hand: &H,
        sweep: S,
        guess0: [f64; N],
    );
}

/// Visits the three closed-form rows with the mechanism values of `closed_form_step`, passed
/// through `black_box` (so that no harness folds them into its code).
pub fn closed_form_rows(v: &mut impl RowVisitor) {
    let p = black_box(rhombic::PARAMS);
    let sweep = RhombicSweep::<RHOMBIC_TERMS>::new(&p, TURN_720, PERIOD);
    v.row("rhombic", "rhombic drive", p.kinloop(), &ClosedForm::new(&p), sweep, rhombic::initial_guess(&p));
    let four = black_box(FOUR_BAR);
    let four_hand = FourBarClosed::of(&four);
    let g: [f64; 2] = four.solve(0.0).expect("the four-bar assembles").q.into();
    let sweep = FourBarSweep::<FOUR_BAR_TERMS>::new(four_hand, TURN_720, PERIOD, g);
    v.row("four_bar", "four-bar with its coupler point", four, &four_hand, sweep, g);
    let gear = black_box(gear_lever());
    let gear_hand = GearLeverClosed::of(&gear);
    let g: [f64; 2] = gear.solve(0.0).expect("the gear lever assembles").q.into();
    let sweep = GearLeverSweep::<GEAR_LEVER_TERMS>::new(gear_hand, TURN_720, PERIOD, g);
    v.row("gear_lever", "gear-lever rocker", gear, &gear_hand, sweep, g);
}
