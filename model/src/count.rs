//! How kinloop writes a count in a message: the number and its noun, singular for one.

/// A count `n` of the regular noun `noun` (given in the singular) as a message writes it: `1
/// input`, `0 inputs`, `2 inputs`: the runtime's [`kinloop_runtime::Count`], whose messages count
/// alike. Public here so that the command line writes its counts as the model's messages do.
///
/// ```
/// use kinloop_model::Count;
/// assert_eq!(Count(1, "input").to_string(), "1 input");
/// assert_eq!(Count(0, "value").to_string(), "0 values");
/// assert_eq!(Count(3, "unknown").to_string(), "3 unknowns");
/// ```
pub use kinloop_runtime::Count;

#[cfg(test)]
mod tests {
    use super::Count;
    use crate::StepFailure;
    use crate::{Model, ParamScanConfig};
    use kinloop_runtime::dims::{KinBuf, Sizes};
    use kinloop_runtime::dynamics::SpeedLaw;
    use kinloop_runtime::generated::BlockFailure;

    /// A slider-crank of one input and two unknowns, with a body: dynamics to run.
    const SLIDER_CRANK: &str = "pub struct SliderCrank {
        params r = 1, l = 3, m = 2;
        input phi;
        unknowns beta = 0, s = 4;
        loop rod: r @ phi + l @ beta == (s, 0);
        body slider: mass m, com (s, 0);
    }";

    #[test]
    fn one_is_singular_and_every_other_count_plural() {
        assert_eq!(Count(1, "input").to_string(), "1 input");
        for (n, text) in [(0, "0 inputs"), (2, "2 inputs"), (11, "11 inputs"), (21, "21 inputs")] {
            assert_eq!(Count(n, "input").to_string(), text);
        }
    }

    /// The model's messages about sizes given name one of a thing in the singular.
    #[test]
    fn messages_count_one_in_the_singular() {
        let mut m = Model::read("slider_crank.kl", SLIDER_CRANK).expect("the declaration reads");
        let e = m.assembly_modes(&[0.1, 0.2]).expect_err("two inputs for one").to_string();
        assert!(e.contains("needs 1 input, not 2"), "{e}");
        let e = m.inverse_cycle(SpeedLaw::Constant(1.0)).guess(&[0.1]).run().expect_err("one value for two");
        assert!(e.to_string().contains("a guess of 1 value given, 2 expected"), "{e}");
        let state = KinBuf::zeros(Sizes { n: 1, ni: 1, no: 0 });
        let e = m.load_values(&state).expect_err("one unknown for two").to_string();
        assert!(e.contains("a state of 1 input and 1 unknown given, 1 and 2 expected"), "{e}");
        let spec = ParamScanConfig::new(&[0.0], &[1.0], 3);
        let r = m.scan(&["r"], &[[1.0, 2.0]], &spec, |_: &[f64]| 0, |a, _: &[f64], _: &KinBuf| a);
        let e = r[0].clone().expect_err("two values for one parameter").to_string();
        assert!(e.contains("a parameter set of 2 values for the 1 parameter scanned"), "{e}");
        // A block's failure after one iteration, as the evaluator says it.
        let fail = BlockFailure::NoConvergence { row: 0, iterations: 1, residual: 0.5 };
        let e = StepFailure::Block(fail).to_string();
        assert!(e.starts_with("no convergence after 1 iteration: "), "{e}");
    }
}
