//! A recorded motion: the poses of a sweep and the events where it stopped, without the
//! mechanism's const generics, so one drawing description serves any mechanism.

use super::error::DrawError;
use kinloop_runtime::dims::{Dims, KinBuf};
use kinloop_runtime::drawing::{Columns, Drawable};
use kinloop_runtime::{Compiled, Error, Event, EventKind, Kernel, Kin, Mechanism, QuantityKind, Sweep, SweepOf};

/// One pose of the mechanism: inputs `x`, unknowns `q` and output columns `out`, in
/// declaration order (as in [`Kin`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// Input values.
    pub x: Vec<f64>,
    /// Unknowns (positions).
    pub q: Vec<f64>,
    /// Output columns (`p.x`, `p.y` for each point, then scalar outputs, as declared).
    pub out: Vec<f64>,
}

impl<const N: usize, const NI: usize, const NO: usize> From<&Kin<N, NI, NO>> for Pose {
    fn from(k: &Kin<N, NI, NO>) -> Self {
        Pose { x: k.x.to_vec(), q: k.q.to_vec(), out: k.out.to_vec() }
    }
}

impl From<&KinBuf> for Pose {
    fn from(k: &KinBuf) -> Self {
        Pose { x: k.x.to_vec(), q: k.q.to_vec(), out: k.out.to_vec() }
    }
}

/// A singular position met by the sweep, with the mechanism's pose there.
#[derive(Clone, Debug, PartialEq)]
pub struct Marked {
    /// Limit position or singular crossing.
    pub kind: EventKind,
    /// The pose at the located event.
    pub pose: Pose,
}

/// The poses of a sweep, in order, and its events (see [`Motion::record`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// Names of the inputs (`Mechanism::INPUTS`).
    pub inputs: Vec<String>,
    /// Kinds of the inputs (`Mechanism::INPUT_KINDS`): an angle is read out in degrees. A
    /// missing kind reads as a plain number.
    pub input_kinds: Vec<QuantityKind>,
    /// Names of the output columns (`Mechanism::OUTPUTS`).
    pub outputs: Vec<String>,
    /// The samples, in sweep order.
    pub poses: Vec<Pose>,
    /// The located events (limit positions, singular crossings), in the order met.
    pub events: Vec<Marked>,
    /// The sweep stopped at its last event (rather than passing it or reaching its end).
    pub stopped: bool,
}

impl Motion {
    /// A motion without poses for mechanism `M`, to fill with [`Motion::push`].
    pub fn empty<M, const N: usize, const NI: usize, const NO: usize>() -> Motion
    where
        M: Mechanism<N, NI, NO>,
    {
        Motion::with_columns(Columns::of::<M, N, NI, NO>())
    }

    /// A motion without poses of any [`Drawable`] mechanism (compiled, or a
    /// `kinloop_model::Model` read at run time), to fill with [`Motion::push`] or
    /// [`Motion::follow`].
    pub fn of<D: Drawable + ?Sized>(m: &D) -> Motion {
        Motion::with_columns(m.columns())
    }

    fn with_columns(c: Columns) -> Motion {
        Motion {
            inputs: c.inputs,
            input_kinds: c.input_kinds,
            outputs: c.outputs,
            poses: Vec::new(),
            events: Vec::new(),
            stopped: false,
        }
    }

    /// Appends a pose: to draw the mechanism at any state, or the states of a sweep the caller
    /// ran itself (`state.flat` of a generated `NameState`, or a [`Kin`]).
    ///
    /// ```
    /// use kinloop_viz::draw::{Drawing, Motion, Pt};
    ///
    /// kinloop::mechanism! {
    ///     pub struct SliderCrank {
    ///         params r = 1.0, l = 3.0;
    ///         input phi;
    ///         unknowns psi = 0, x = r + l;
    ///         loop oabo: r @ phi == (x, 0) + l @ psi;
    ///         point b = r @ phi;
    ///         point c = (x, 0);
    ///     }
    /// }
    /// let m = SliderCrank::default();
    /// let mut one = Motion::empty::<SliderCrank, 2, 1, 4>();
    /// one.push(&m.solve(0.7)?.flat);
    /// let d = Drawing::new().pivot(Pt::fixed(0.0, 0.0)).link([Pt::fixed(0.0, 0.0), Pt::point("b"), Pt::point("c")]).slider("c", 0.0);
    /// let svg = d.svg(&one, 0)?;
    /// assert!(svg.starts_with("<svg") && !svg.contains("<animate"));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn push(&mut self, pose: impl Into<Pose>) {
        self.poses.push(pose.into());
    }

    /// Runs `sweep` of mechanism `m` to its end and records every sample. A stop at a located
    /// limit position or singular crossing ([`Error::SweepStopped`]) ends the motion there: the
    /// events are kept with the pose at each (drawn and marked by the drawings) and
    /// [`Motion::stopped`] is set. Any other failure is [`DrawError::Sweep`].
    /// See the [module documentation](super) for an example.
    pub fn record<M, S, const N: usize, const NI: usize, const NO: usize>(
        m: &M,
        sweep: Sweep<'_, M, S, N, NI, NO>,
    ) -> Result<Motion, DrawError>
    where
        M: Mechanism<N, NI, NO>,
        S: From<Kin<N, NI, NO>>,
    {
        let mut motion = Motion::empty::<M, N, NI, NO>();
        let events = motion.follow(sweep)?;
        motion.mark(&mut Compiled(m), &events);
        Ok(motion)
    }

    /// Runs `sweep` (over any [`Kernel`]: a compiled mechanism's, or a run-time model's) to its
    /// end and appends every sample, as [`Motion::record`] does; returns the sweep's events,
    /// for [`Motion::mark`] (their poses need the mechanism, which the sweep holds until it is
    /// dropped). A stop at a located event sets [`Motion::stopped`]; any other failure is
    /// [`DrawError::Sweep`].
    pub fn follow<K, S>(&mut self, mut sweep: SweepOf<K, S>) -> Result<Vec<Event>, DrawError>
    where
        K: Kernel,
        S: From<<K::Dims as Dims>::Kin>,
        for<'k> Pose: From<&'k <K::Dims as Dims>::Kin>,
    {
        while let Some(k) = sweep.next_kin() {
            match k {
                Ok(k) => self.push(&k),
                Err(Error::SweepStopped { .. }) => self.stopped = true,
                Err(e) => return Err(DrawError::Sweep(e)),
            }
        }
        Ok(sweep.events().to_vec())
    }

    /// Appends `events` (of a sweep of `m`, from [`Motion::follow`]) with the mechanism's pose
    /// at each: its outputs evaluated at the event's position. An event whose outputs cannot be
    /// evaluated is left out.
    pub fn mark<D: Drawable + ?Sized>(&mut self, m: &mut D, events: &[Event]) {
        for e in events {
            let Some(out) = m.outputs_at(&e.x, &e.q) else {
                continue;
            };
            self.events.push(Marked { kind: e.kind, pose: Pose { x: e.x.clone(), q: e.q.clone(), out } });
        }
    }

    /// Checks every pose against the motion's columns (a [`Pose`] pushed by hand can have any
    /// lengths): one input value per input name, one output value per output column, the
    /// same number of unknowns in every pose; and every input finite (the readout and the
    /// events' labels print them).
    pub(crate) fn check(&self) -> Result<(), DrawError> {
        let unknowns = self.poses.first().map_or(0, |p| p.q.len());
        for (pose, p) in self.all_poses().enumerate() {
            for (part, len, expected) in [
                ("input", p.x.len(), self.inputs.len()),
                ("unknown", p.q.len(), unknowns),
                ("output column", p.out.len(), self.outputs.len()),
            ] {
                if len != expected {
                    return Err(DrawError::MalformedPose { pose, part, len, expected });
                }
            }
        }
        // Inputs are printed (the readout, the events' labels): none may be NaN or infinite.
        for (pose, p) in self.all_poses().enumerate() {
            if let Some(i) = p.x.iter().position(|v| !v.is_finite()) {
                let what = match pose.checked_sub(self.poses.len()) {
                    Some(j) => format!("input `{}` of event {j}", self.inputs[i]),
                    None => format!("input `{}`", self.inputs[i]),
                };
                return Err(DrawError::NonFinite { what, pose });
            }
        }
        Ok(())
    }

    /// The samples followed by the event poses: the poses a drawing must fit in its frame.
    pub(crate) fn all_poses(&self) -> impl Iterator<Item = &Pose> {
        self.poses.iter().chain(self.events.iter().map(|e| &e.pose))
    }

    /// The names of the mechanism's points (output column pairs `p.x`, `p.y`).
    pub fn point_names(&self) -> Vec<String> {
        self.outputs
            .iter()
            .filter_map(|c| c.strip_suffix(".x"))
            .filter(|p| self.outputs.iter().any(|c| c.strip_suffix(".y") == Some(p)))
            .map(str::to_string)
            .collect()
    }

    /// The output columns of point `name`.
    pub(crate) fn point_columns(&self, name: &str) -> Result<(usize, usize), DrawError> {
        let col = |axis: &str| self.outputs.iter().position(|c| *c == format!("{name}.{axis}"));
        match (col("x"), col("y")) {
            (Some(ix), Some(iy)) => Ok((ix, iy)),
            _ => Err(DrawError::UnknownPoint { name: name.to_string(), available: self.point_names() }),
        }
    }
}
