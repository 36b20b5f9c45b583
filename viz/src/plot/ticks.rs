//! Tick positions and labels: steps of 1, 2, 2.5 or 5 times a power of ten, and for angles
//! (in degrees) the divisions of a turn (15, 30, 45, 90, 180, 360 degrees).

/// The ticks of one axis over its (possibly widened) range, in shown units.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Ticks {
    /// The axis range (the data range, widened to whole steps when asked).
    pub lo: f64,
    pub hi: f64,
    pub step: f64,
    /// Tick values in `[lo, hi]`.
    pub values: Vec<f64>,
}

/// The smallest "nice" step of at least `raw`.
fn nice_step(raw: f64, angle: bool) -> f64 {
    if angle && raw > 1.0 {
        const TURN: [f64; 9] = [2.0, 5.0, 10.0, 15.0, 30.0, 45.0, 90.0, 180.0, 360.0];
        if let Some(&s) = TURN.iter().find(|&&s| s >= raw) {
            return s;
        }
        return 360.0 * nice_step(raw / 360.0, false);
    }
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0].iter().map(|m| m * mag).find(|&s| s >= raw * (1.0 - 1e-12)).unwrap_or(10.0 * mag)
}

impl Ticks {
    /// Ticks for data in `[lo, hi]` (shown units): about six intervals for angles (90 degree
    /// steps over a turn), about seven otherwise. `widen` extends the range to whole steps (for
    /// value axes, so the frame ends on labelled ticks). A zero-width range is opened around
    /// its value.
    pub fn new(lo: f64, hi: f64, angle: bool, widen: bool) -> Ticks {
        let (lo, hi) = if hi > lo {
            (lo, hi)
        } else {
            let half = if lo == 0.0 { 1.0 } else { 0.05 * lo.abs() };
            (lo - half, hi + half)
        };
        let step = nice_step((hi - lo) / if angle { 6.0 } else { 7.0 }, angle);
        // Integer multiples of the step, with a tolerance of rounding for ends on a tick.
        let slack = 1e-9;
        let (lo, hi) =
            if widen { ((lo / step + slack).floor() * step, (hi / step - slack).ceil() * step) } else { (lo, hi) };
        Ticks { lo, hi, step, values: Ticks::multiples(lo, hi, step) }
    }

    /// The multiples of `step` in `[lo, hi]` (ends within rounding included).
    pub fn multiples(lo: f64, hi: f64, step: f64) -> Vec<f64> {
        let slack = 1e-9;
        let (first, last) = ((lo / step - slack).ceil() as i64, (hi / step + slack).floor() as i64);
        (first..=last).map(|k| if k == 0 { 0.0 } else { k as f64 * step }).collect()
    }

    /// The label of tick `v`: as many decimals as the step needs, or scientific notation for
    /// very large or very small values.
    pub fn label(&self, v: f64) -> String {
        let decimals = (0..=12).find(|&d| {
            let s = self.step * 10f64.powi(d);
            (s - s.round()).abs() < 1e-6 * s
        });
        let big = self.lo.abs().max(self.hi.abs());
        match decimals {
            Some(d) if d <= 5 && big < 1e6 => format!("{:.*}", d as usize, v),
            _ => {
                let e = big.log10().floor() as i32;
                let mant_step = self.step / 10f64.powi(e);
                let d = (0..=12).find(|&d| {
                    let s = mant_step * 10f64.powi(d);
                    (s - s.round()).abs() < 1e-6 * s
                });
                format!("{:.*}e{e}", d.unwrap_or(3) as usize, v / 10f64.powi(e))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(t: &Ticks) -> Vec<String> {
        t.values.iter().map(|&v| t.label(v)).collect()
    }

    #[test]
    fn a_turn_is_ticked_every_90_degrees() {
        let t = Ticks::new(0.0, 360.0, true, false);
        assert_eq!(labels(&t), ["0", "90", "180", "270", "360"]);
        let t = Ticks::new(0.0, 180.0, true, false);
        assert_eq!(t.step, 30.0);
        let t = Ticks::new(-30.0, 40.0, true, true);
        assert_eq!(t.step, 15.0);
        assert_eq!((t.lo, t.hi), (-30.0, 45.0));
    }

    #[test]
    fn linear_steps_are_one_two_or_five_times_a_power_of_ten() {
        let t = Ticks::new(0.013, 0.092, false, true);
        assert_eq!(labels(&t), ["0.00", "0.02", "0.04", "0.06", "0.08", "0.10"]);
        let t = Ticks::new(-2.3, 2.1, false, true);
        assert_eq!(labels(&t), ["-3", "-2", "-1", "0", "1", "2", "3"]);
        assert!(t.values.contains(&0.0) && t.lo <= -2.3 && t.hi >= 2.1);
        let t = Ticks::new(2.0e-6, 9.0e-6, false, true);
        assert!(labels(&t).iter().all(|l| l.contains('e')), "{:?}", labels(&t));
        let t = Ticks::new(5.0, 5.0, false, true);
        assert!(t.lo < 5.0 && t.hi > 5.0);
    }
}
