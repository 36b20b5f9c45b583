//! Shared by the dynamics tests: the rhombic drive (declared once, in the
//! fixtures crate) with a mass model, and the independent references built from
//! solved positions only (no analogs): configurations of the bodies, Richardson-extrapolated
//! central differences, kinetic energy and virtual work.

use crate::support::newton_to_fine_step;
use kinloop::Mechanism;
use kinloop::dynamics::{Body, Coord, MassModel, Rotation};

pub use kinloop_fixtures::{FourBar, RhombicDrive, StirlingEngine};

/// Index of a named output column or unknown of a mechanism.
pub fn index(names: &[&str], name: &str) -> usize {
    names.iter().position(|n| *n == name).unwrap_or_else(|| panic!("no column `{name}`"))
}

/// The drive with plausible masses (kg, kg·length²): crank, two rods, the working piston C and
/// the displacer F as declared by [`StirlingEngine`] (its default masses, no gas), plus a gas
/// force on the piston that depends on its position.
pub fn rhombic_model(gravity: [f64; 2]) -> MassModel<4, 1, 7> {
    let xc = index(&<RhombicDrive as Mechanism<4, 1, 7>>::UNKNOWNS, "x_c");
    let at = [Coord::Unknown(xc), Coord::Fixed(0.0)];
    rhombic_bodies(gravity).with_force("gas", at, move |k, _| [gas_force(k.q[xc]), 0.0]).expect("a valid load")
}

/// The bodies of [`rhombic_model`] without the gas force, from the declaration.
pub fn rhombic_bodies(gravity: [f64; 2]) -> MassModel<4, 1, 7> {
    StirlingEngine::default().mass_model().and_then(|m| m.with_gravity(gravity)).expect("a valid model")
}

/// The same bodies built by hand, by index: the independent check of the declaration.
pub fn rhombic_bodies_by_hand(gravity: [f64; 2]) -> MassModel<4, 1, 7> {
    let out = |n| Coord::Output(index(&<RhombicDrive as Mechanism<4, 1, 7>>::OUTPUTS, n));
    let unknown = |n| index(&<RhombicDrive as Mechanism<4, 1, 7>>::UNKNOWNS, n);
    let de = RhombicDrive::default().de;
    MassModel::new()
        .with_gravity(gravity)
        .and_then(|m| {
            m.with_body(Body {
                name: "crank".into(),
                mass: 2.0,
                com: [out("s1.x"), out("s1.y")],
                inertia: 0.05,
                rotation: Rotation::Input(0),
            })
        })
        .and_then(|m| {
            let rotation = Rotation::Unknown(unknown("phi2"));
            m.with_body(Body {
                name: "working rod".into(),
                mass: 0.8,
                com: [out("s2.x"), out("s2.y")],
                inertia: 0.6,
                rotation,
            })
        })
        .and_then(|m| {
            let rotation = Rotation::Unknown(unknown("phi4"));
            m.with_body(Body {
                name: "displacer rod".into(),
                mass: 0.9,
                com: [out("s4.x"), out("s4.y")],
                inertia: 0.9,
                rotation,
            })
        })
        .and_then(|m| {
            let com = [Coord::Unknown(unknown("x_c")), Coord::Fixed(0.0)];
            m.with_body(Body { name: "piston".into(), mass: 1.5, com, inertia: 0.0, rotation: Rotation::None })
        })
        .and_then(|m| {
            let com = [Coord::Unknown(unknown("x_f")), Coord::Fixed(de)];
            m.with_body(Body { name: "displacer".into(), mass: 1.1, com, inertia: 0.0, rotation: Rotation::None })
        })
        .expect("a valid model")
}

/// Gas force on the working piston along x, a smooth function of its position (compression
/// towards the crank side raises it).
pub fn gas_force(x_c: f64) -> f64 {
    -20.0 / (x_c + 4.6).powi(2)
}

/// Value of a coordinate from positions.
pub fn coord<const N: usize, const NO: usize>(q: &[f64; N], out: &[f64; NO], c: Coord) -> f64 {
    match c {
        Coord::Output(o) => out[o],
        Coord::Unknown(u) => q[u],
        Coord::Fixed(v) => v,
    }
}

/// A body's angle from positions (0 for a slider).
pub fn angle<const N: usize>(x: f64, q: &[f64; N], r: Rotation) -> f64 {
    match r {
        Rotation::Unknown(u) => q[u],
        Rotation::Input(_) => x,
        Rotation::None => 0.0,
    }
}

/// `[x, y, theta]` of every body, from a position solve only (warm-started at `guess`).
pub fn configuration<M, const N: usize, const NO: usize>(m: &M, bodies: &[Body], x: f64, guess: &[f64; N]) -> Vec<f64>
where
    M: Mechanism<N, 1, NO>,
{
    let (q, _) = m.position_flat(&[x], guess, &newton_to_fine_step()).expect("position solve");
    let out = m.outputs_flat(&[x], &q);
    bodies
        .iter()
        .flat_map(|b| [coord(&q, &out, b.com[0]), coord(&q, &out, b.com[1]), angle(x, &q, b.rotation)])
        .collect()
}

/// First derivative of a vector function by central differences at `h` and `h / 2`, one
/// Richardson step: truncation O(h^4), rounding ~ eps |f| / h.
pub fn derivative(f: impl Fn(f64) -> Vec<f64>, x: f64, h: f64) -> Vec<f64> {
    let d = |h: f64| -> Vec<f64> { f(x + h).iter().zip(f(x - h)).map(|(a, b)| (a - b) / (2.0 * h)).collect() };
    d(h / 2.0).iter().zip(d(h)).map(|(a, b)| (4.0 * a - b) / 3.0).collect()
}

/// Second derivative likewise (truncation O(h^4), rounding ~ eps |f| / h^2).
pub fn second_derivative(f: impl Fn(f64) -> Vec<f64>, x: f64, h: f64) -> Vec<f64> {
    let f0 = f(x);
    let d = |h: f64| -> Vec<f64> {
        f(x + h).iter().zip(f(x - h)).zip(&f0).map(|((a, b), c)| (a - 2.0 * c + b) / (h * h)).collect()
    };
    d(h / 2.0).iter().zip(d(h)).map(|(a, b)| (4.0 * a - b) / 3.0).collect()
}

/// Reduced moment of inertia `2 T / omega^2` from finite-difference velocities of the solved
/// positions: `sum m |dr_S/dphi|^2 + J_S (dtheta/dphi)^2`.
pub fn reduced_inertia_fd<M, const N: usize, const NO: usize>(m: &M, bodies: &[Body], x: f64, guess: &[f64; N]) -> f64
where
    M: Mechanism<N, 1, NO>,
{
    let v = derivative(|x| configuration(m, bodies, x, guess), x, 1e-3);
    bodies
        .iter()
        .enumerate()
        .map(|(i, b)| b.mass * (v[3 * i].powi(2) + v[3 * i + 1].powi(2)) + b.inertia * v[3 * i + 2].powi(2))
        .sum()
}

kinloop::mechanism! {
    /// Offset slider-crank: crank `r` at the origin, rod `l`, piston on the line y = e; the
    /// crank pin as a point.
    pub struct SliderCrank {
        params r = 1.0, l = 3.5, e = 0.3;
        input phi;
        unknowns psi = pi, x = r + l;
        loop oabo: r @ phi == (x, e) + l @ psi;
        point pin = r @ phi;
    }
}
