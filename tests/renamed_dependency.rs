//! A crate that depends on kinloop under another name (`kl = { package = "kinloop", .. }` in
//! its `Cargo.toml`), or reaches it through a crate of its own that re-exports it, declares
//! mechanisms with `kl::mechanism!` and nothing else.
//!
//! Cargo's rename, in this test crate: `extern crate self as kinloop;` makes `::kinloop` name
//! this crate, which has none of kinloop's items, so any path of an expansion that names the
//! facade `::kinloop` fails to resolve, as it does where `::kinloop` names nothing; kinloop
//! itself is linked only as `kl` (an `extern crate` loads a crate by its `--extern` name, which
//! the extern prelude's `kinloop` does not change). A test binary of its own, since the
//! renaming holds for the whole crate.

extern crate kinloop as kl;
extern crate self as kinloop;

/// A crate's facade that re-exports kinloop's macro under its own path.
mod facade {
    pub use kl::mechanism;
}

kl::mechanism! {
    /// Slider-crank with a coupler point, an output, a body and loads, and the sensitivities:
    /// every part of the generated code that names the runtime.
    #[kinloop(sensitivities)]
    pub struct SliderCrank {
        params r = 1.0, l = 3.0, m = 2.0, g = 9.81;
        input phi;
        unknowns psi = 0, x = r + l;
        loop oabc: r @ phi + l @ psi == (x, 0);
        point mid = r @ phi + 0.5 * l @ psi;
        output gap = x - r;
        body rod: mass m, com mid, inertia m * l * l / 12, turns psi;
        force push at mid = (1, 0);
        gravity (0, -g);
    }
}

facade::mechanism! {
    /// A five-bar of two inputs, solved by Newton, declared through the re-export.
    #[kinloop(newton)]
    pub struct FiveBar {
        params a = 1.0, b = 2.5, c = 2.5, d = 1.0, e = 2.0;
        inputs th1, th2;
        unknowns al = 1.2, be = 2.0;
        loop l: a @ th1 + b @ al == (e, 0) + d @ th2 + c @ be;
        point p = a @ th1 + b @ al;
    }
}

mod imported {
    use kl::mechanism;

    mechanism! {
        /// A four-bar, declared by the imported macro.
        pub struct FourBar {
            params a = 1.0, b = 3.0, c = 2.5, d = 3.2;
            input phi;
            unknowns beta = 0.5, gamma = 1.5;
            loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
        }
    }
}

/// The mechanisms declared under the other name solve: the slider-crank's slider position is
/// the closed form `r cos(phi) + sqrt(l^2 - r^2 sin^2(phi))`, to rounding of numbers of order
/// one (1e-12 is a thousand ulps of 4, the largest length).
#[test]
fn mechanisms_declared_through_another_name_solve() -> Result<(), kl::Error> {
    let m = SliderCrank::default();
    let phi = 0.3_f64;
    let s = m.solve(phi)?;
    let x = phi.cos() + (9.0 - phi.sin().powi(2)).sqrt();
    assert!((s.q.x - x).abs() < 1e-12, "{} against {x}", s.q.x);
    let (_, sens) = m.sensitivities(phi, &s.q)?;
    // `x` grows with the rod one for one: `dx/dl = l / sqrt(l^2 - r^2 sin^2(phi))`.
    let dx_dl = 3.0 / (9.0 - phi.sin().powi(2)).sqrt();
    assert!((sens.q.x.l - dx_dl).abs() < 1e-12, "{} against {dx_dl}", sens.q.x.l);

    let five = FiveBar::default();
    let k = five.solve([0.2, 1.7])?;
    let (a, b, c, d, e) = (1.0, 2.5, 2.5, 1.0, 2.0);
    let closure_x = a * 0.2f64.cos() + b * k.q.al.cos() - e - d * 1.7f64.cos() - c * k.q.be.cos();
    assert!(closure_x.abs() < 1e-12, "{closure_x}");

    let four = imported::FourBar::default();
    let s = four.solve(0.3)?;
    let closure = 0.3f64.cos() + 3.0 * s.q.beta.cos() - 3.2 - 2.5 * s.q.gamma.cos();
    assert!(closure.abs() < 1e-12, "{closure}");
    Ok(())
}

/// With kinloop's feature `serde`, the generated structs implement serde's traits through the
/// facade's own serde, named by the derives from the runtime path the expansion was given.
#[cfg(feature = "serde")]
#[test]
fn generated_structs_serialize_under_another_name() {
    fn serde_both<T: kl::__gen::serde::Serialize + for<'de> kl::__gen::serde::Deserialize<'de>>() {}
    serde_both::<SliderCrank>();
    serde_both::<SliderCrankState>();
    serde_both::<FiveBarState>();
    serde_both::<imported::FourBarUnknowns>();
}
