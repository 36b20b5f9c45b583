//! One libm call for an angle's sine and cosine, for the peers written by hand.
//!
//! `f64::sin_cos` is two calls, `sin` and `cos`, which LLVM merges into glibc's `sincos` only
//! where both stay in one basic block. A cosine used only after a branch (the hand closed form's
//! `?` on a root that may not exist) is sunk past it and both calls are paid: about 45
//! instructions an angle more than `sincos` (callgrind, the rhombic drive's hand closed form).
//! kinloop's sines and cosines of an input are computed where they are used, so LLVM merges them;
//! a reference must not pay for the accident. This calls `sincos` itself where glibc has it.

/// `(x.sin(), x.cos())` from glibc's `sincos` (the same values: one routine computes both), or
/// from `f64::sin_cos` on other targets.
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        unsafe extern "C" {
            fn sincos(x: f64, sin: *mut f64, cos: *mut f64);
        }
        let (mut s, mut c) = (0.0, 0.0);
        // SAFETY: glibc's `sincos` writes one `f64` through each pointer, both to live locals.
        unsafe { sincos(x, &mut s, &mut c) };
        (s, c)
    }
    #[cfg(not(all(target_os = "linux", target_env = "gnu")))]
    {
        x.sin_cos()
    }
}

#[cfg(test)]
mod tests {
    use std::hint::black_box;

    use super::sin_cos;

    #[test]
    fn the_values_of_sin_and_cos() {
        // glibc computes `sincos` with the code of its `sin` and `cos` (`s_sin.c`): the same
        // bits as each routine on its own, over several turns and tiny and huge arguments.
        // Through `black_box`, each of `sin` and `cos` a call of its own (LLVM would merge the
        // pair into `sincos` in an optimised build, and the test compare `sincos` with itself).
        let each = |x: f64| (black_box(x).sin(), black_box(x).cos());
        for k in -2000..=2000 {
            let x = f64::from(k) * 0.0173;
            assert_eq!(sin_cos(x), each(x), "{x}");
        }
        for x in [0.0, -0.0, 1e-300, 1e-8, 3.0e5, 1.0e22, f64::MAX] {
            assert_eq!(sin_cos(x), each(x), "{x}");
        }
        let (s, c) = sin_cos(f64::NAN);
        assert!(s.is_nan() && c.is_nan());
    }
}
