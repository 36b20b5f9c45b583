//! Tick positions and labels: steps of 1, 2, 2.5 or 5 times a power of ten, and for angles
//! (in degrees) the divisions of a turn (15, 30, 45, 90, 180, 360 degrees).

/// The ticks of one axis over its (possibly widened) range.
///
/// Everything is held in *scaled* shown units: a value `v` (library units) is held as
/// `v / unit * factor`, with `unit` a power of two near the largest magnitude of the data
/// (dividing by it is exact) and `factor` the shown units per library unit. Scaled, every
/// finite range spans at most a few units, so no difference, step or pixel overflows, and a
/// subnormal range is as precise as a normal one. Steps and labels are exact decimals
/// (`mant * 10^exp` and integer multiples of it), never computed from the scaled values.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Ticks {
    /// The power of two the values are divided by (library units).
    pub unit: f64,
    /// Shown units per library unit (degrees per radian for angles, else 1).
    pub factor: f64,
    /// The axis range (the data range, padded and widened to whole steps when asked), scaled.
    pub lo: f64,
    pub hi: f64,
    /// The step, scaled.
    pub step: f64,
    /// The step in shown units is `mant * 10^exp` (`mant` without trailing zeros).
    pub mant: i64,
    pub exp: i32,
    /// The ticks in `[lo, hi]`: their scaled value and their index `k` (the tick shows
    /// `k * mant * 10^exp`).
    pub values: Vec<(f64, i128)>,
}

/// The largest power of two not above `m` (1 for 0): dividing by it is exact, and brings `m`
/// into `[1, 2)`.
pub(crate) fn binade(m: f64) -> f64 {
    if !(m.is_finite() && m > 0.0) {
        return 1.0;
    }
    let bits = m.to_bits();
    if m.is_normal() {
        f64::from_bits(bits & 0x7ff0_0000_0000_0000)
    } else {
        // A subnormal: its highest set bit.
        f64::from_bits(1u64 << (63 - bits.leading_zeros()))
    }
}

/// `log10` of a power of two (exact exponent times log10 2).
fn log10_of_binade(unit: f64) -> f64 {
    let bits = unit.to_bits();
    let exponent =
        if unit.is_normal() { ((bits >> 52) & 0x7ff) as i32 - 1023 } else { 63 - bits.leading_zeros() as i32 - 1074 };
    exponent as f64 * std::f64::consts::LOG10_2
}

/// `mant * 10^exp` with the trailing zeros of `mant` moved into `exp`.
fn normalised(mut mant: i64, mut exp: i32) -> (i64, i32) {
    while mant != 0 && mant % 10 == 0 {
        mant /= 10;
        exp += 1;
    }
    (mant, exp)
}

/// `mant * 10^exp` as an f64 (correctly rounded for small exponents; infinite or zero beyond
/// the range).
fn decimal_value(mant: i64, exp: i32) -> f64 {
    if exp >= 0 { mant as f64 * 10f64.powi(exp) } else { mant as f64 / 10f64.powi(-exp) }
}

/// The smallest "nice" step of at least `raw` (shown units) as `(mant, exp)`: 1, 2, 2.5 or 5
/// times a power of ten, or for angles of more than a degree a division of a turn (15, 30,
/// 45, 90, 180, 360 degrees) or 360 times a nice number. `lg` is `log10(raw)`, used where
/// `raw` itself is out of the f64 range (then `raw` is 0 or infinite).
fn nice_step(raw: f64, lg: f64, angle: bool) -> (i64, i32) {
    let direct = (1e-290..=1e290).contains(&raw);
    let lg = if direct { raw.log10() } else { lg };
    if angle && lg > 0.0 {
        const TURN: [i64; 9] = [2, 5, 10, 15, 30, 45, 90, 180, 360];
        if let Some(&s) = TURN.iter().find(|&&s| s as f64 >= raw) {
            return normalised(s, 0);
        }
        let (m, e) = nice_step(raw / 360.0, lg - 360f64.log10(), false);
        return normalised(360 * m, e);
    }
    let e = lg.floor();
    // `raw / 10^e` in [1, 10).
    let (r, mag) = if direct { (raw, 10f64.powf(e)) } else { (10f64.powf(lg - e), 1.0) };
    let steps = [(1, 0), (2, 0), (25, -1), (5, 0), (1, 1)];
    let (m, de) = steps.into_iter().find(|&(m, de)| decimal_value(m, de) * mag >= r * (1.0 - 1e-12)).unwrap_or((1, 1));
    normalised(m, e as i32 + de)
}

/// `k * 10^p` written with `max(0, -p)` decimals, exactly (from the integer).
pub(crate) fn decimal(k: i128, p: i32) -> String {
    let digits = k.unsigned_abs().to_string();
    let sign = if k < 0 { "-" } else { "" };
    if p >= 0 {
        return if k == 0 { "0".into() } else { format!("{sign}{digits}{}", "0".repeat(p as usize)) };
    }
    let d = p.unsigned_abs() as usize;
    let digits = format!("{digits:0>width$}", width = d + 1);
    let (whole, frac) = digits.split_at(digits.len() - d);
    format!("{sign}{whole}.{frac}")
}

/// The range `[lo, hi]` padded by `pad` times its width on each side, the pad stopping at
/// zero.
fn padded(lo: f64, hi: f64, pad: f64) -> (f64, f64) {
    let (plo, phi) = (lo - pad * (hi - lo), hi + pad * (hi - lo));
    (if lo >= 0.0 { plo.max(0.0) } else { plo }, if hi <= 0.0 { phi.min(0.0) } else { phi })
}

/// The scaled range `[lo, hi]` padded (see [`padded`]), a zero-width one opened around its
/// value.
fn opened(lo: f64, hi: f64, pad: f64) -> (f64, f64) {
    // The pad never crosses zero: data that are all non-negative (an amplitude, a length from
    // a datum) get an axis from 0, not one reaching below it for the pad alone.
    let (lo, hi) = padded(lo, hi, pad);
    if hi > lo {
        (lo, hi)
    } else {
        let half = if lo == 0.0 { 1.0 } else { 0.05 * lo.abs() };
        (lo - half, hi + half)
    }
}

impl Ticks {
    /// Ticks for data in `[lo, hi]` (library units, finite), shown times `factor`: about six
    /// intervals for angles (90 degree steps over a turn), about seven otherwise. The range
    /// is first padded by `pad` times its width; `widen` then extends it to whole steps (for
    /// value axes, so the frame ends on labelled ticks). A zero-width range is opened around
    /// its value.
    pub fn new(lo: f64, hi: f64, factor: f64, angle: bool, widen: bool, pad: f64) -> Ticks {
        let unit = binade(lo.abs().max(hi.abs()));
        Ticks::scaled(lo / unit * factor, hi / unit * factor, unit, factor, angle, widen, pad)
    }

    /// [`Ticks::new`] for a range already scaled by `unit` and `factor`.
    pub fn scaled(lo: f64, hi: f64, unit: f64, factor: f64, angle: bool, widen: bool, pad: f64) -> Ticks {
        let (lo, hi) = opened(lo, hi, pad);
        Ticks::stepped(lo, hi, unit, factor, angle, widen, if angle { 6.0 } else { 7.0 })
    }

    /// Ticks for values in `[lo, hi]` (finite, already in shown units: degrees for angles),
    /// about `intervals` of them, the range widened to whole steps and not padded: a small
    /// chart's axis (the interactive pages'), with the steps and labels of the plot module's.
    pub fn widened(lo: f64, hi: f64, angle: bool, intervals: f64) -> Ticks {
        let unit = binade(lo.abs().max(hi.abs()));
        let (lo, hi) = opened(lo / unit, hi / unit, 0.0);
        Ticks::stepped(lo, hi, unit, 1.0, angle, true, intervals)
    }

    /// Ticks over the scaled range `[lo, hi]` (`hi > lo`), about `intervals` steps.
    fn stepped(lo: f64, hi: f64, unit: f64, factor: f64, angle: bool, widen: bool, intervals: f64) -> Ticks {
        let raw = (hi - lo) / intervals;
        let (mant, exp) = nice_step(raw * unit, raw.log10() + log10_of_binade(unit), angle);
        let shown = decimal_value(mant, exp);
        let step = if shown.is_normal() && (shown / unit).is_normal() {
            shown / unit
        } else {
            mant as f64 * 10f64.powf(exp as f64 - log10_of_binade(unit))
        };
        // Integer multiples of the step, with a tolerance of rounding for ends on a tick.
        let slack = 1e-9;
        let (lo, hi) = if widen {
            ((lo / step + slack).floor() * step, (hi / step - slack).ceil() * step)
        } else {
            // An end a little short of a tick is taken to it (a sweep over [0, 2 pi) ends a
            // sample before the turn: the axis still ends on the 360 tick): within a tenth of
            // the range for angles (a turn sampled at 12 points or more), a twentieth otherwise.
            let near = (hi - lo) * if angle { 0.1 } else { 0.05 };
            let (below, above) = ((lo / step + slack).floor() * step, (hi / step - slack).ceil() * step);
            (if lo - below <= near { below } else { lo }, if above - hi <= near { above } else { hi })
        };
        Ticks { unit, factor, lo, hi, step, mant, exp, values: Ticks::multiples(lo, hi, step) }
    }

    /// Ticks at every whole number in `[lo, hi]` (unscaled, not an angle): abscissae such as
    /// the orders of harmonics, each labelled.
    pub fn whole(lo: f64, hi: f64) -> Ticks {
        Ticks { unit: 1.0, factor: 1.0, lo, hi, step: 1.0, mant: 1, exp: 0, values: Ticks::multiples(lo, hi, 1.0) }
    }

    /// Ticks over the scaled range `[lo, hi]` at the scale and step of `other`.
    pub fn with_step(lo: f64, hi: f64, other: &Ticks) -> Ticks {
        Ticks { lo, hi, values: Ticks::multiples(lo, hi, other.step), ..other.clone() }
    }

    /// The multiples of `step` in `[lo, hi]` (ends within rounding included), with their
    /// indices.
    fn multiples(lo: f64, hi: f64, step: f64) -> Vec<(f64, i128)> {
        let slack = 1e-9;
        let (first, last) = ((lo / step - slack).ceil() as i128, (hi / step + slack).floor() as i128);
        (first..=last).map(|k| (if k == 0 { 0.0 } else { k as f64 * step }, k)).collect()
    }

    /// Where value `v` (library units) falls on the axis: 0 at `lo`, 1 at `hi`.
    pub fn frac(&self, v: f64) -> f64 {
        self.frac_scaled(v / self.unit * self.factor)
    }

    /// Where scaled value `v` falls on the axis: 0 at `lo`, 1 at `hi`.
    pub fn frac_scaled(&self, v: f64) -> f64 {
        (v - self.lo) / (self.hi - self.lo)
    }

    /// The label of tick `k`: as many decimals as the step needs, or scientific notation for
    /// very large or very small values (steps below 1e-5, values of a million or more), all
    /// of one axis with the power of ten of its largest end (`"0.5e-6"`, `"1.5e-6"`); zero is
    /// then `"0"`.
    pub fn label(&self, k: i128) -> String {
        let big = self.lo.abs().max(self.hi.abs());
        let shown = big * self.unit;
        let lg = if shown.is_normal() { shown.log10() } else { big.log10() + log10_of_binade(self.unit) };
        let value = k * self.mant as i128;
        if self.exp >= -5 && shown < 1e6 && shown.is_normal() {
            decimal(value, self.exp)
        } else if value == 0 {
            "0".into()
        } else {
            let e = lg.floor() as i32;
            format!("{}e{e}", decimal(value, self.exp - e))
        }
    }

    /// The label of tick `k` as its difference from tick `base` (`k >= base`), in the style
    /// of [`Ticks::label`] for an axis from zero to the range's width: few digits where the
    /// values themselves need many (far from zero, varying little).
    pub fn difference_label(&self, k: i128, base: i128) -> String {
        let width = Ticks { lo: 0.0, hi: self.hi - self.lo, ..self.clone() };
        width.label(k - base)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(t: &Ticks) -> Vec<String> {
        t.values.iter().map(|&(_, k)| t.label(k)).collect()
    }

    #[test]
    fn a_turn_is_ticked_every_90_degrees() {
        let t = Ticks::new(0.0, 360.0, 1.0, true, false, 0.0);
        assert_eq!(labels(&t), ["0", "90", "180", "270", "360"]);
        let t = Ticks::new(0.0, 180.0, 1.0, true, false, 0.0);
        assert_eq!(t.step * t.unit, 30.0);
        let t = Ticks::new(-30.0, 40.0, 1.0, true, true, 0.0);
        assert_eq!(t.step * t.unit, 15.0);
        assert_eq!((t.lo * t.unit, t.hi * t.unit), (-30.0, 45.0));
    }

    #[test]
    fn a_sampled_turn_ends_on_the_360_tick_and_padding_stays_above_zero() {
        // 72 samples over [0, 2 pi): the last is at 355 degrees.
        let t = Ticks::new(0.0, 355.0, 1.0, true, false, 0.0);
        assert_eq!(labels(&t), ["0", "90", "180", "270", "360"]);
        // 300 degrees is no full turn: the axis ends at the data.
        let t = Ticks::new(0.0, 300.0, 1.0, true, false, 0.0);
        assert_eq!(t.hi * t.unit, 300.0);
        // Amplitudes from 12 to 5800 with the value axes' 3 % pad: the axis starts at 0.
        let t = Ticks::new(12.0, 5800.0, 1.0, false, true, 0.03);
        assert_eq!(labels(&t)[0], "0");
        let t = Ticks::new(-5800.0, -12.0, 1.0, false, true, 0.03);
        assert_eq!(labels(&t).last().map(String::as_str), Some("0"));
    }

    #[test]
    fn linear_steps_are_one_two_or_five_times_a_power_of_ten() {
        let t = Ticks::new(0.013, 0.092, 1.0, false, true, 0.0);
        assert_eq!(labels(&t), ["0.00", "0.02", "0.04", "0.06", "0.08", "0.10"]);
        let t = Ticks::new(-2.3, 2.1, 1.0, false, true, 0.0);
        assert_eq!(labels(&t), ["-3", "-2", "-1", "0", "1", "2", "3"]);
        assert!(t.values.iter().any(|v| v.0 == 0.0) && t.lo * t.unit <= -2.3 && t.hi * t.unit >= 2.1);
        let t = Ticks::new(2.0e-6, 9.0e-6, 1.0, false, true, 0.0);
        assert_eq!(labels(&t), ["2e-6", "3e-6", "4e-6", "5e-6", "6e-6", "7e-6", "8e-6", "9e-6"]);
        let t = Ticks::new(5.0, 5.0, 1.0, false, true, 0.0);
        assert!(t.lo * t.unit < 5.0 && t.hi * t.unit > 5.0);
    }

    #[test]
    fn zero_is_0_on_an_axis_labelled_with_a_power_of_ten() {
        let t = Ticks::new(-2.3e-6, 2.1e-6, 1.0, false, true, 0.0);
        assert_eq!(labels(&t), ["-3e-6", "-2e-6", "-1e-6", "0", "1e-6", "2e-6", "3e-6"]);
        let t = Ticks::new(0.0, 6.5e9, 1.0, false, true, 0.0);
        assert_eq!(labels(&t), ["0", "1e9", "2e9", "3e9", "4e9", "5e9", "6e9", "7e9"]);
        // Decimals keep the step's digits, zero too.
        let t = Ticks::new(-0.0023, 0.0021, 1.0, false, true, 0.0);
        assert_eq!(labels(&t), ["-0.003", "-0.002", "-0.001", "0.000", "0.001", "0.002", "0.003"]);
    }

    #[test]
    fn a_small_charts_axis_has_fewer_steps_and_the_same_labels() {
        let t = Ticks::widened(-1.0e-6, 1.4e-6, false, 5.0);
        assert_eq!(labels(&t), ["-1.0e-6", "-0.5e-6", "0", "0.5e-6", "1.0e-6", "1.5e-6"]);
        assert_eq!((t.lo * t.unit, t.hi * t.unit), (-1.0e-6, 1.5e-6));
        let t = Ticks::widened(0.0, 180.0, true, 5.0);
        assert_eq!(labels(&t), ["0", "45", "90", "135", "180"]);
        consistent(&Ticks::widened(7.0, 7.0, false, 5.0));
        consistent(&Ticks::widened(0.0, 0.0, true, 5.0));
        consistent(&Ticks::widened(-1e100, 1e100, false, 5.0));
    }

    /// Every tick of `t` at its place: labels parse back to finite numbers, increasing by
    /// the step, each at its scaled value; the range is finite and not empty.
    fn consistent(t: &Ticks) {
        assert!(t.lo.is_finite() && t.hi.is_finite() && t.hi > t.lo && t.step > 0.0, "{t:?}");
        assert!(!t.values.is_empty() && t.values.len() < 20, "{t:?}");
        // The labels of one axis share their exponent (if any): their mantissas increase.
        let shown: Vec<f64> =
            labels(t).iter().map(|l| l.split('e').next().unwrap().parse().expect("a number")).collect();
        assert!(shown.iter().all(|v| v.is_finite()), "{:?}", labels(t));
        for (w, l) in t.values.windows(2).zip(shown.windows(2)) {
            assert!(w[1].0 > w[0].0 && l[1] > l[0], "{:?}", labels(t));
        }
        for &(v, _) in &t.values {
            assert!(t.frac_scaled(v) >= -1e-6 && t.frac_scaled(v) <= 1.0 + 1e-6, "{t:?}");
        }
    }

    #[test]
    fn every_finite_range_is_ticked_with_finite_labels() {
        // Ranges whose width overflows, subnormal ranges, a range a few ulps wide at the top
        // of the f64 range: all scaled, none gives NaN or infinity.
        let t = Ticks::new(-1e308, 1e308, 1.0, false, true, 0.03);
        consistent(&t);
        assert_eq!(labels(&t)[0], "-1.5e308");
        let t = Ticks::new(0.0, 1e-320, 1.0, false, false, 0.0);
        consistent(&t);
        assert_eq!(labels(&t)[..2], ["0", "0.2e-320"], "{:?}", labels(&t));
        consistent(&Ticks::new(f64::MIN, f64::MAX, 1.0, false, true, 0.03));
        consistent(&Ticks::new(5e-324, 5e-324, 1.0, false, true, 0.03));
        consistent(&Ticks::new(f64::MAX, f64::MAX, 1.0, false, true, 0.0));
        let top = f64::MAX;
        consistent(&Ticks::new(top - 4.0 * 2f64.powi(971), top, 1.0, false, true, 0.0));
        // Angles whose degrees overflow.
        let t = Ticks::new(-1e307, 1e307, 180.0 / std::f64::consts::PI, true, false, 0.0);
        consistent(&t);
        assert_eq!(labels(&t), ["-3.6e308", "0", "3.6e308"]);
        assert_eq!(decimal(-25, -3), "-0.025");
        assert_eq!(decimal(0, -2), "0.00");
        assert_eq!(decimal(12, 2), "1200");
        let b = binade(1e-320);
        assert!(b <= 1e-320 && 2.0 * b > 1e-320);
        assert_eq!(binade(3.0), 2.0);
    }
}
