//! The mechanisms of the benchmarks, each declared once: [`declare!`] both invokes
//! `kinloop::mechanism!` on the declaration and keeps its text, so the expansion benchmark and
//! the code-size report expand exactly what is compiled and timed.

/// `declare!(CONST => { body })`: `kinloop::mechanism! { body }` plus `pub const CONST: &str`
/// holding the body's text.
macro_rules! declare {
    ($(#[$doc:meta])* $text:ident => { $($body:tt)* }) => {
        kinloop::mechanism! { $($body)* }
        $(#[$doc])*
        pub const $text: &str = stringify!($($body)*);
    };
}

declare! {
    /// The rhombic drive of SEEDS.md 000 as timed: the four unknowns, no output points.
    RHOMBIC_DRIVE => {
        /// Asymmetric rhombic drive with a developed crank (SEEDS.md 000, Fig. 1).
        pub struct RhombicDrive {
            params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, de = 0.9, gamma = 0.7;
            input phi1;
            unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
            loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
            loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
        }
    }
}

declare! {
    /// The rhombic drive as the paper and the main example declare it: with the centres of
    /// mass of the crank and of both rods.
    RHOMBIC_DRIVE_PAPER => {
        /// Rhombic drive with centres of mass (SEEDS.md 000).
        pub struct RhombicDrivePaper {
            params r_p = 1.0, r_b = 1.2, l_p = 3.0, l_b = 3.5, e_p = 0.5, de = 0.9, gamma = 0.7,
                   l_as1 = 0.3, psi_s1 = 0.35, l_cs2 = 1.2, l_fs4 = 1.4;
            input phi1;
            unknowns phi2 = 0, phi4 = pi, x_c = -l_p, x_f = l_b;
            loop oabco:   (0, e_p) + r_p @ phi1           == (x_c, 0)  + l_p @ phi2;
            loop oadff1o: (0, e_p) + r_b @ (phi1 + gamma) == (x_f, de) + l_b @ phi4;
            point s1 = (0, e_p) + l_as1 @ (phi1 + psi_s1);
            point s2 = (x_c, 0) + l_cs2 @ phi2;
            point s4 = (x_f, de) + l_fs4 @ phi4;
        }
    }
}

declare! {
    /// The class IV mechanism of SEEDS.md 003: one coupled block of four unknowns.
    CLASS_FOUR => {
        /// Class IV mechanism: crank OA, ternary links CAE and DBF, binary links CD and EF.
        pub struct ClassFour {
            params oa = 1.0, xb = 4.4, yb = 0.6, ac = 2.3, ae = 2.4, alpha_a = 0.84,
                   bd = 1.6, bf = 3.5, alpha_b = 0.62, cd = 2.0, ef = 3.4;
            input phi;
            unknowns th1 = 1.4, th2 = 3.0, psi1 = -0.8, psi2 = -1.0;
            let a = oa @ phi;
            let b = (xb, yb);
            loop acdb: a + ac @ th1 + cd @ psi1 == b + bd @ th2;
            loop aefb: a + ae @ (th1 + alpha_a) + ef @ psi2 == b + bf @ (th2 + alpha_b);
        }
    }
}

declare! {
    /// The gear-lever drive of SEEDS.md 001 (as in `tests/gear_lever.rs`).
    GEAR_LEVER => {
        /// Gear-lever drive with a slotted rocker.
        pub struct GearLever {
            params l_c = 2.0, l_p = 1.2, u = 3.0;
            input alpha;
            unknowns s = l_c + l_p, phi = 0;
            let pin = (l_c * sin(alpha), l_c * cos(alpha))
                    + (l_p * sin((1 - u) * alpha), l_p * cos((1 - u) * alpha));
            loop oab: pin == s * (sin(phi), cos(phi));
            point b = pin;
        }
    }
}

declare! {
    /// The five-bar linkage with two inputs (as in `tests/five_bar.rs`).
    FIVE_BAR => {
        /// Five-bar linkage.
        pub struct FiveBar {
            params a = 1.0, b = 2.5, c = 2.2, d = 1.5, e = 1.2;
            inputs th1, th2;
            unknowns phi2 = 1.0, phi3 = 2.0;
            loop abcde: a @ th1 + b @ phi2 == (d, 0) + e @ th2 + c @ phi3;
            point pc = a @ th1 + b @ phi2;
            output spread = phi3 - phi2;
        }
    }
}

declare! {
    /// The roller edger of SEEDS.md 002 with time as the input (as in `tests/roller_edger.rs`).
    ROLLER_EDGER => {
        /// Lever-turning mode of the roller edger.
        pub struct RollerEdger {
            params l1, l3, l5, alpha, v1, l2, s2, l4, l6, beta;
            input t;
            unknowns phi1 = 1.0, phi3 = -1.0, phi2 = 2.0, phi4 = 0.5;
            let s1 = v1 * t;
            loop o1ao3:  (s1 + l1) @ phi1 + l3 @ phi3 == l5 @ alpha;
            loop o2bao3: (s2 + l2) @ phi2 + l4 @ phi4 + l3 @ phi3 == l6 @ beta;
        }
    }
}

/// A declaration of the benchmarks: its name, its text, and its number of scalar equations.
#[derive(Clone, Copy, Debug)]
pub struct Declaration {
    pub name: &'static str,
    pub text: &'static str,
    pub equations: usize,
}

/// The paper mechanisms, in the order of the report.
pub fn paper_mechanisms() -> [Declaration; 6] {
    [
        Declaration { name: "RhombicDrive", text: RHOMBIC_DRIVE, equations: RhombicDrive::EQUATIONS.len() },
        Declaration {
            name: "RhombicDrivePaper",
            text: RHOMBIC_DRIVE_PAPER,
            equations: RhombicDrivePaper::EQUATIONS.len(),
        },
        Declaration { name: "ClassFour", text: CLASS_FOUR, equations: ClassFour::EQUATIONS.len() },
        Declaration { name: "GearLever", text: GEAR_LEVER, equations: GearLever::EQUATIONS.len() },
        Declaration { name: "FiveBar", text: FIVE_BAR, equations: FiveBar::EQUATIONS.len() },
        Declaration { name: "RollerEdger", text: ROLLER_EDGER, equations: RollerEdger::EQUATIONS.len() },
    ]
}
