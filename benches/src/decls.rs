//! The mechanisms of the benchmarks. The gallery's (`kinloop-fixtures`) keep their declarations'
//! text, so the expansion benchmark and the code-size report expand exactly what is compiled.
//! The rhombic drive and the class IV mechanism are timed without output points, so a step
//! computes the unknowns and their analogs only, as the hand-written peers do: the class IV one
//! is the fixtures' `ClassFourCore` (the gallery's body without its points); the rhombic drive's
//! is declared here, with the seven kinematic parameters only.

use kinloop_fixtures::declare;
use kinloop_fixtures::gear_lever::{GEAR_LEVER_TEXT, GearLever};
use kinloop_fixtures::roller_edger::{ROLLER_EDGER_TEXT, RollerEdger};
use kinloop_fixtures::{FIVE_BAR_TEXT, FiveBar, RHOMBIC_DRIVE_TEXT};

declare! {
    /// The rhombic drive of paper 000 as timed: the four unknowns, no output points.
    RHOMBIC_DRIVE => {
        /// Asymmetric rhombic drive with a developed crank (paper 000, Fig. 1), no output points.
        pub struct RhombicDrive {
            params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, de = 0.9, gamma = 0.7;
            input phi1;
            unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
            loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
            loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
        }
    }
}

pub use kinloop_fixtures::class_four::{
    CLASS_FOUR_CORE_TEXT as CLASS_FOUR, ClassFourCore as ClassFour, ClassFourCoreUnknowns as ClassFourUnknowns,
};

pub use kinloop_fixtures::FourBarSens;

/// The four-bar `m` declared with sensitivities.
pub fn four_sens(m: &kinloop_fixtures::FourBar) -> FourBarSens {
    FourBarSens { a: m.a, b: m.b, c: m.c, d: m.d }
}

/// A declaration of the benchmarks: its name, its text, and its number of scalar equations.
#[derive(Clone, Copy, Debug)]
pub struct Declaration {
    /// The mechanism's name, as the report prints it.
    pub name: &'static str,
    /// The declaration's text, expanded by the expansion benchmark.
    pub text: &'static str,
    /// Its number of scalar equations (two per loop), for the report's size column.
    pub equations: usize,
}

/// The paper mechanisms, in the order of the report.
pub fn paper_mechanisms() -> [Declaration; 6] {
    [
        Declaration { name: "RhombicDrive", text: RHOMBIC_DRIVE, equations: RhombicDrive::EQUATIONS.len() },
        Declaration {
            name: "RhombicDrivePaper",
            text: RHOMBIC_DRIVE_TEXT,
            equations: kinloop_fixtures::RhombicDrive::EQUATIONS.len(),
        },
        Declaration { name: "ClassFour", text: CLASS_FOUR, equations: ClassFour::EQUATIONS.len() },
        Declaration { name: "GearLever", text: GEAR_LEVER_TEXT, equations: GearLever::EQUATIONS.len() },
        Declaration { name: "FiveBar", text: FIVE_BAR_TEXT, equations: FiveBar::EQUATIONS.len() },
        Declaration { name: "RollerEdger", text: ROLLER_EDGER_TEXT, equations: RollerEdger::EQUATIONS.len() },
    ]
}
