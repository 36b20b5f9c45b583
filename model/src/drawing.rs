//! A run-time model's drawings: the description the macro emits for its declaration
//! (`Mechanism::DRAWING`, from the same function of the pipeline), and the model as the
//! runtime's [`Drawable`], so that the default drawing, the recorded motion, the SVG
//! animations and the interactive pages are the compiled mechanisms' own code.

use crate::model::Model;
use kinloop_runtime::drawing::{Columns, Drawable};
use kinloop_runtime::{NewtonConfig, SweepConfig};
use kinloop_viz::draw::{DefaultDrawing, DrawError, GridMotion, Motion, Pose};

impl Model {
    /// The default drawing's description in the runtime's text format
    /// (`kinloop_runtime::drawing`): the text the compiled mechanism of the same declaration
    /// holds as `Mechanism::DRAWING`.
    pub fn drawing_text(&self) -> &str {
        &self.drawing
    }

    /// The default drawing, from the declaration: `kinloop_viz`'s
    /// [`DefaultDrawing::of`] over this model, as a compiled mechanism's `drawing()`.
    ///
    /// ```
    /// use kinloop_model::Model;
    /// use kinloop_viz::draw::Animation;
    /// let text = "pub struct FourBar {
    ///     params a = 1, b = 3, c = 2.5, d = 3.2;
    ///     input phi;
    ///     unknowns psi = 0.6, theta = 1.9;
    ///     loop abcd: a @ phi + b @ psi == (d, 0) + c @ theta;
    /// }";
    /// let mut m = Model::read("four_bar.kl", text).unwrap();
    /// let motion = m.motion(&[0.0], &[6.283185307179586], 37, &[0.6, 1.9]).unwrap();
    /// let svg = m.drawing().animate(&motion, &Animation::default()).unwrap();
    /// assert!(svg.contains("<animate ") && !svg.contains("NaN"));
    /// ```
    pub fn drawing(&mut self) -> DefaultDrawing {
        DefaultDrawing::of(self)
    }

    /// The motion of a sweep of `samples` inputs from `from` to `to` from `guess` (as
    /// [`Model::sweep`]), recorded for the drawings as a compiled mechanism's
    /// `Motion::record` records it: every sample, and the located events with the pose at each
    /// (a stop there sets [`Motion::stopped`]).
    ///
    /// # Errors
    /// [`DrawError::Sweep`] when the sweep cannot be made (an unset parameter, wrong sizes, no
    /// sample) or fails otherwise than at a located event.
    pub fn motion(&mut self, from: &[f64], to: &[f64], samples: usize, guess: &[f64]) -> Result<Motion, DrawError> {
        self.motion_with(from, to, samples, guess, self.sweep_config)
    }

    /// [`Model::motion`] with the solver configuration `config`.
    ///
    /// # Errors
    /// As [`Model::motion`].
    pub fn motion_with(
        &mut self,
        from: &[f64],
        to: &[f64],
        samples: usize,
        guess: &[f64],
        config: SweepConfig,
    ) -> Result<Motion, DrawError> {
        let mut motion = Motion::of(self);
        let events = motion.follow(self.sweep_with(from, to, samples, guess, config).map_err(DrawError::Sweep)?)?;
        motion.mark(self, &events);
        Ok(motion)
    }

    /// The model over a grid of its inputs, `counts[k]` values evenly spaced from `from[k]` to
    /// `to[k]` on each axis, from `guess` at `from`, for an interactive page with one slider per
    /// input (`kinloop_viz::html::html_grid_of`): `GridMotion::record` of a compiled mechanism,
    /// the assembly mode carried from cell to cell by this model's sweeps.
    ///
    /// # Errors
    /// As `GridMotion::record`.
    pub fn grid(&mut self, from: &[f64], to: &[f64], counts: &[usize], guess: &[f64]) -> Result<GridMotion, DrawError> {
        let motion = Motion::of(self);
        GridMotion::record_by(motion, from, to, counts, guess, |from, to, samples, guess| {
            Ok(self.sweep(from, to, samples, guess)?.last().map(|k| k.map(|k| Pose::from(&k))))
        })
    }
}

/// The model as its drawings read it: the same description, parameters, columns, reference
/// state and outputs as the compiled mechanism of its declaration.
impl Drawable for Model {
    fn name(&self) -> &str {
        Model::name(self)
    }
    fn description_text(&self) -> &str {
        &self.drawing
    }
    /// `NaN` for a parameter without a value: whatever depends on it is not drawn (the sweep
    /// that records a motion fails first, naming the parameter).
    fn param_values(&self) -> Vec<f64> {
        Model::param_values(self).iter().map(|v| v.unwrap_or(f64::NAN)).collect()
    }
    fn columns(&self) -> Columns {
        Columns {
            inputs: self.inputs().to_vec(),
            input_kinds: self.input_kinds().to_vec(),
            unknowns: self.unknowns().to_vec(),
            unknown_kinds: self.unknown_kinds().to_vec(),
            outputs: self.outputs().to_vec(),
            output_kinds: self.output_kinds().to_vec(),
        }
    }
    /// The positions alone (the compiled `position_flat`, as the compiled reference): a
    /// mechanism whose analogs are singular at inputs 0 still has its reference state.
    fn reference(&mut self) -> Option<Vec<f64>> {
        let x = vec![0.0; self.inputs().len()];
        let mut guess = vec![0.0; self.unknowns().len()];
        self.guess(&x, &mut guess).ok()?;
        Some(self.positions(&x, &guess, &NewtonConfig::default()).ok()?.to_vec())
    }
    fn outputs_at(&mut self, x: &[f64], q: &[f64]) -> Option<Vec<f64>> {
        let mut out = vec![0.0; self.outputs().len()];
        Model::outputs_at(self, x, q, &mut out).ok()?;
        Some(out)
    }
}
