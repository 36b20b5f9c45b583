//! Fourier coefficients of a periodic quantity over one cycle.
//!
//! With `n` equally spaced samples `v_j = v(x0 + j T / n)`, `j = 0 .. n - 1`, over one period
//! `T`, the coefficients of
//!
//! ```text
//! v(x) ≈ a0 + sum_{k=1..m} a_k cos(k θ) + b_k sin(k θ),     θ = 2 π (x - x0) / T
//! ```
//!
//! are `a0 = (1/n) sum v_j`, `a_k = (2/n) sum v_j cos(2 π k j / n)`,
//! `b_k = (2/n) sum v_j sin(2 π k j / n)`: the trapezoidal rule for the integrals
//! `a0 = 1/(2π) ∫ v dθ`, `a_k = 1/π ∫ v cos kθ dθ`, `b_k = 1/π ∫ v sin kθ dθ` over a turn.
//! For a trigonometric polynomial of degree below `n / 2` they are exact (to rounding); for a
//! smooth periodic quantity (the kinematics of a crank mechanism) the error falls geometrically
//! with `n`. The angles `2 π k j / n` are reduced exactly (`k j mod n`) before the cosine, so
//! high harmonics lose no accuracy.

use crate::error::Error;
use std::f64::consts::TAU;

/// Fourier coefficients of a periodic quantity; see the [module documentation](self).
#[derive(Clone, Debug, PartialEq)]
pub struct Fourier {
    /// Start of the cycle (`θ = 0`).
    pub x0: f64,
    /// The period in input units.
    pub period: f64,
    /// The mean value.
    pub a0: f64,
    /// Cosine coefficients `a_1 ..= a_m` (`a[k - 1]` is `a_k`).
    pub a: Vec<f64>,
    /// Sine coefficients `b_1 ..= b_m`.
    pub b: Vec<f64>,
}

impl Fourier {
    /// Highest harmonic held.
    pub fn harmonics(&self) -> usize {
        self.a.len()
    }

    /// Amplitude `sqrt(a_k^2 + b_k^2)` of harmonic `k >= 1` (`|a0|` for `k = 0`; 0 beyond the
    /// highest harmonic held).
    pub fn amplitude(&self, k: usize) -> f64 {
        match k {
            0 => self.a0.abs(),
            k if k <= self.a.len() => self.a[k - 1].hypot(self.b[k - 1]),
            _ => 0.0,
        }
    }

    /// The truncated series up to harmonic `m` (at most [`Fourier::harmonics`]) at `x`, with its
    /// first and second derivatives with respect to `x`.
    ///
    /// Scale-free in the input's unit: the phase is the fraction of the period reached, and
    /// each derivative is a sum over the harmonics divided by the period once per order, so a
    /// period in a tiny or a huge unit gives the same values (the derivatives scaled by the
    /// unit's powers). The frequency `2 pi / T` itself overflows for a period below about
    /// `3.5e-308`, and its square for one below about `5e-154` (or underflows to zero for one
    /// above about `4e154`), where the series and its derivatives need not.
    pub fn eval_upto(&self, m: usize, x: f64) -> (f64, f64, f64) {
        let theta = TAU * ((x - self.x0) / self.period);
        let (mut v, mut s1, mut s2) = (self.a0, 0.0, 0.0);
        for k in 1..=m.min(self.a.len()) {
            let kf = k as f64;
            let (s, c) = (kf * theta).sin_cos();
            let (a, b) = (self.a[k - 1], self.b[k - 1]);
            v += a * c + b * s;
            // Derivatives with respect to the phase; `d theta / dx = 2 pi / T` comes after.
            s1 += kf * (b * c - a * s);
            s2 -= kf * kf * (a * c + b * s);
        }
        let per_period = |sum: f64| TAU * (sum / self.period);
        (v, per_period(s1), TAU * per_period(s2 / self.period))
    }

    /// The series with every harmonic held, at `x`.
    pub fn eval(&self, x: f64) -> f64 {
        self.eval_upto(self.a.len(), x).0
    }
}

/// Fourier coefficients up to harmonic `harmonics` of `n = values.len()` equally spaced samples
/// over one period starting at `x0` (the sample at `x0 + period` is not included: it repeats the
/// first). Needs `harmonics < n / 2`, so that every coefficient is resolved (no aliasing).
///
/// ```
/// use kinloop_runtime::analysis::fourier::fourier;
/// use std::f64::consts::TAU;
/// // v = 0.5 + 2 cos x - 0.25 sin 3x, sampled 16 times over [0, 2 pi).
/// let v: Vec<f64> = (0..16).map(|j| {
///     let x = TAU * j as f64 / 16.0;
///     0.5 + 2.0 * x.cos() - 0.25 * (3.0 * x).sin()
/// }).collect();
/// let f = fourier(&v, 0.0, TAU, 5)?;
/// assert!((f.a0 - 0.5).abs() < 1e-15 && (f.a[0] - 2.0).abs() < 1e-15 && (f.b[2] + 0.25).abs() < 1e-15);
/// assert!(f.amplitude(2) < 1e-15 && f.amplitude(4) < 1e-15);
/// # Ok::<(), kinloop_runtime::Error>(())
/// ```
pub fn fourier(values: &[f64], x0: f64, period: f64, harmonics: usize) -> Result<Fourier, Error> {
    let n = values.len();
    // (`2 * harmonics` overflows for a count near `usize::MAX`.)
    if n == 0 {
        return Err(Error::InvalidArgument("Fourier coefficients need samples over the period; got none".into()));
    }
    if harmonics >= n.div_ceil(2) {
        let samples = if n == 1 { "1 sample resolves".to_string() } else { format!("{n} samples resolve") };
        return Err(Error::InvalidArgument(format!(
            "{samples} harmonics below {}, not {harmonics}: ask for fewer harmonics, or give at least {} samples",
            n.div_ceil(2),
            harmonics.saturating_mul(2).saturating_add(1)
        )));
    }
    if !(period.is_finite() && period > 0.0) {
        return Err(Error::InvalidArgument(format!("the period must be positive and finite, got {period}")));
    }
    // (A start not finite was refused as a period not finite, naming the good period.)
    if !x0.is_finite() {
        return Err(Error::InvalidArgument(format!("the start of the period must be finite, got {x0}")));
    }
    if let Some(j) = values.iter().position(|v| !v.is_finite()) {
        return Err(Error::InvalidArgument(format!("sample {j} is not finite")));
    }
    let nf = n as f64;
    // Sums of samples near the largest f64 overflow (five samples of 1e308 sum to infinity)
    // where the coefficients, at most twice the largest sample, need not: such samples are
    // summed scaled down by a power of two, which is exact, and the coefficients scaled back.
    let largest = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let down = if largest > f64::MAX / (4.0 * nf) { (4.0 * nf).log2().ceil() as i32 } else { 0 };
    let scaled: Vec<f64>;
    let values = if down > 0 {
        scaled = values.iter().map(|v| v * 2f64.powi(-down)).collect();
        &scaled[..]
    } else {
        values
    };
    // Tables of cos and sin of 2 pi i / n, indexed by the exact residue k j mod n.
    let (cos, sin): (Vec<f64>, Vec<f64>) = (0..n)
        .map(|i| {
            let (s, c) = (TAU * i as f64 / nf).sin_cos();
            (c, s)
        })
        .unzip();
    let a0 = values.iter().sum::<f64>() / nf;
    let mut a = Vec::with_capacity(harmonics);
    let mut b = Vec::with_capacity(harmonics);
    for k in 1..=harmonics {
        let (mut sa, mut sb) = (0.0, 0.0);
        for (j, v) in values.iter().enumerate() {
            let r = (k * j) % n;
            sa += v * cos[r];
            sb += v * sin[r];
        }
        a.push(2.0 * sa / nf);
        b.push(2.0 * sb / nf);
    }
    let mut f = Fourier { x0, period, a0, a, b };
    if down > 0 {
        let up = 2f64.powi(down);
        f.a0 *= up;
        f.a.iter_mut().chain(&mut f.b).for_each(|c| *c *= up);
        if !(f.a0.is_finite() && f.a.iter().chain(&f.b).all(|c| c.is_finite())) {
            return Err(Error::InvalidArgument("the Fourier coefficients of these samples overflow f64".into()));
        }
    }
    Ok(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trigonometric_polynomial_is_recovered_exactly() {
        // Degree 7 with every coefficient set, on a shifted, scaled period: exact with n = 16.
        let (x0, period) = (0.3, 2.5);
        let a0 = 0.7;
        let a = [1.2, -0.4, 0.0, 0.05, 0.3, -0.01, 0.002];
        let b = [-0.6, 0.25, 0.125, 0.0, -0.2, 0.03, -0.004];
        let v = |x: f64| {
            let th = TAU * (x - x0) / period;
            a0 + (1..=7).map(|k| a[k - 1] * (k as f64 * th).cos() + b[k - 1] * (k as f64 * th).sin()).sum::<f64>()
        };
        for n in [16, 17, 64, 1000] {
            let s: Vec<f64> = (0..n).map(|j| v(x0 + period * j as f64 / n as f64)).collect();
            let f = fourier(&s, x0, period, 7).unwrap();
            assert!((f.a0 - a0).abs() < 1e-13, "n = {n}");
            for k in 0..7 {
                assert!((f.a[k] - a[k]).abs() < 1e-13, "n = {n}, a{}: {} vs {}", k + 1, f.a[k], a[k]);
                assert!((f.b[k] - b[k]).abs() < 1e-13, "n = {n}, b{}: {} vs {}", k + 1, f.b[k], b[k]);
            }
            // The series and its derivatives reproduce the polynomial (derivatives term by term).
            let w = TAU / period;
            let deriv = |x: f64, order: i32| {
                let th = w * (x - x0);
                (1..=7)
                    .map(|k| {
                        let kw = k as f64 * w;
                        let (sn, cs) = (k as f64 * th).sin_cos();
                        let (a, b) = (a[k - 1], b[k - 1]);
                        if order == 1 { kw * (b * cs - a * sn) } else { -kw * kw * (a * cs + b * sn) }
                    })
                    .sum::<f64>()
            };
            for x in [0.0, 0.77, 2.9] {
                let (y, d1, d2) = f.eval_upto(7, x);
                assert!((y - v(x)).abs() < 1e-13);
                assert!((d1 - deriv(x, 1)).abs() < 1e-12);
                assert!((d2 - deriv(x, 2)).abs() < 1e-11);
            }
        }
        let s: Vec<f64> = (0..16).map(|j| v(x0 + period * j as f64 / 16.0)).collect();
        let f = fourier(&s, x0, period, 7).unwrap();
        assert!((f.amplitude(1) - 1.2f64.hypot(0.6)).abs() < 1e-13);
        assert_eq!(f.amplitude(9), 0.0);
    }

    /// The series and its derivatives in any unit of the input: a period of 2.5 in units of
    /// `u` (and the quantity a length in that unit) gives the same value and analogs as in
    /// units of 1, scaled by `u`'s powers, against the closed form. By a power of two the
    /// samples, coefficients and period scale exactly, so only the evaluation's rounding is
    /// left: the tolerances of `trigonometric_polynomial_is_recovered_exactly`. The frequency
    /// `2 pi / T` squared overflowed at `u = 2^-1000` (the second derivative infinite or NaN)
    /// and underflowed at `u = 2^1000` (zero); a period below 3.5e-308 made the value NaN.
    #[test]
    fn the_series_is_scale_free_in_the_unit_of_the_input() {
        let a0 = 0.7;
        let a = [1.2, -0.4, 0.0, 0.05, 0.3, -0.01, 0.002];
        let b = [-0.6, 0.25, 0.125, 0.0, -0.2, 0.03, -0.004];
        // The polynomial in units of 1, period 2.5 from 0.3, and its first two derivatives.
        let (x0, period) = (0.3, 2.5);
        let w = TAU / period;
        let jet = |x: f64| {
            let th = w * (x - x0);
            let mut out = [a0, 0.0, 0.0];
            for k in 1..=7 {
                let (kw, (sn, cs)) = (k as f64 * w, (k as f64 * th).sin_cos());
                let (a, b) = (a[k - 1], b[k - 1]);
                out[0] += a * cs + b * sn;
                out[1] += kw * (b * cs - a * sn);
                out[2] -= kw * kw * (a * cs + b * sn);
            }
            out
        };
        for u in [2f64.powi(-1000), 2f64.powi(-500), 1.0, 2f64.powi(500), 2f64.powi(1000)] {
            let s: Vec<f64> = (0..16).map(|j| u * jet(x0 + period * j as f64 / 16.0)[0]).collect();
            let f = fourier(&s, x0 * u, period * u, 7).unwrap();
            for x in [0.0, 0.77, 2.9] {
                let (y, d1, d2) = f.eval_upto(7, x * u);
                let want = jet(x);
                assert!((y / u - want[0]).abs() < 1e-13, "u = {u:e}: {y:e} vs {}", want[0]);
                assert!((d1 - want[1]).abs() < 1e-12, "u = {u:e}: {d1:e} vs {}", want[1]);
                assert!((d2 * u - want[2]).abs() < 1e-11, "u = {u:e}: {d2:e} vs {}", want[2]);
            }
        }
        // A dimensionless quantity over a period of 2.5e-308: its value, where the frequency
        // overflows (its derivatives are beyond f64 in that unit).
        let p = 2.5e-308;
        let s: Vec<f64> = (0..16).map(|j| jet(x0 + period * j as f64 / 16.0)[0]).collect();
        let f = fourier(&s, 0.0, p, 7).unwrap();
        for x in [0.0, 0.77, 2.9] {
            let y = f.eval_upto(7, (x - x0) / period * p).0;
            assert!((y - jet(x)[0]).abs() < 1e-13, "{y} vs {}", jet(x)[0]);
        }
    }

    #[test]
    fn smooth_periodic_function_converges_geometrically() {
        // 1 / (1.25 - cos x) = (4/3) (1 + 2 sum 2^-k cos kx): a_k = (8/3) 2^-k.
        let s: Vec<f64> = (0..64).map(|j| 1.0 / (1.25 - (TAU * j as f64 / 64.0).cos())).collect();
        let f = fourier(&s, 0.0, TAU, 10).unwrap();
        assert!((f.a0 - 4.0 / 3.0).abs() < 1e-14);
        for k in 1..=10 {
            assert!((f.a[k - 1] - 8.0 / 3.0 * 0.5f64.powi(k as i32)).abs() < 1e-14, "k = {k}");
            assert!(f.b[k - 1].abs() < 1e-14);
        }
    }

    #[test]
    fn too_many_harmonics_or_bad_data_are_errors() {
        assert!(fourier(&[1.0; 8], 0.0, 1.0, 4).is_err());
        assert!(fourier(&[1.0; 8], 0.0, 1.0, 3).is_ok());
        assert!(fourier(&[1.0; 8], 0.0, 0.0, 1).is_err());
        assert!(fourier(&[1.0, f64::NAN, 1.0, 1.0, 1.0], 0.0, 1.0, 1).is_err());
        // A start not finite is named as such, not as the (good) period.
        for x0 in [f64::NAN, f64::INFINITY] {
            let r = fourier(&[1.0; 8], x0, 1.0, 1);
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("start of the period")), "{r:?}");
        }
    }

    /// No samples, or too few for the harmonics asked, are told so with what to give: without
    /// samples the message was "0 samples resolve harmonics below 0, not 0".
    #[test]
    fn too_few_samples_say_what_to_give() {
        let none = fourier(&[], 0.0, 1.0, 0);
        assert!(matches!(&none, Err(Error::InvalidArgument(m)) if m.contains("got none")), "{none:?}");
        let one = fourier(&[1.0], 0.0, 1.0, 1);
        let says = "1 sample resolves harmonics below 1, not 1: ask for fewer harmonics, or give at least 3 samples";
        assert!(matches!(&one, Err(Error::InvalidArgument(m)) if m == says), "{one:?}");
        assert!(fourier(&[1.0], 0.0, 1.0, 0).is_ok());
    }

    /// A count of harmonics whose double overflows is an error, not an overflow panic (a debug
    /// build) or, wrapped to a small double, a vector of that capacity (a release build).
    #[test]
    fn a_count_of_harmonics_near_usize_max_is_an_error() {
        for harmonics in [usize::MAX, usize::MAX / 2 + 1] {
            let r = fourier(&[1.0; 8], 0.0, 1.0, harmonics);
            assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("resolve harmonics below 4")), "{r:?}");
        }
    }

    /// Samples near the largest f64 give their coefficients, not an infinite mean: their sums
    /// overflow, the coefficients need not. Coefficients beyond f64 are an error.
    #[test]
    fn samples_near_the_largest_f64_give_finite_coefficients() {
        // v = 1e308 (0.5 + 0.25 cos x): a0 = 0.5e308, a1 = 0.25e308, to rounding.
        let v: Vec<f64> = (0..16).map(|j| 1e308 * (0.5 + 0.25 * (TAU * j as f64 / 16.0).cos())).collect();
        let f = fourier(&v, 0.0, TAU, 3).unwrap();
        assert!((f.a0 / 1e308 - 0.5).abs() < 1e-15 && (f.a[0] / 1e308 - 0.25).abs() < 1e-15, "{f:?}");
        assert!(f.a[1].abs() < 1e293 && f.b.iter().all(|b| b.abs() < 1e293), "{f:?}");
        // Scaled by a power of two, the same bits as the samples scaled down.
        let small = fourier(&v.iter().map(|x| x / 2f64.powi(200)).collect::<Vec<_>>(), 0.0, TAU, 3).unwrap();
        assert_eq!(f.a0, small.a0 * 2f64.powi(200));
        assert_eq!(f.a[0], small.a[0] * 2f64.powi(200));
        assert_eq!(fourier(&[f64::MAX; 16], 0.0, TAU, 3).unwrap().a0, f64::MAX);
        // A square wave of amplitude f64::MAX: its first harmonic, 4/pi of it, is beyond f64.
        let square: Vec<f64> = (0..16).map(|j| if (j + 4) % 16 < 8 { f64::MAX } else { -f64::MAX }).collect();
        let r = fourier(&square, 0.0, TAU, 3);
        assert!(matches!(&r, Err(Error::InvalidArgument(m)) if m.contains("overflow")), "{r:?}");
    }
}
