//! Design metrics every mechanism designer asks for: the transmission angle, the Grashof class
//! of a four-bar loop, the time (quick-return) ratio, and a report of dead centres and limit
//! positions along a sweep.
//!
//! | metric | helper | computed from |
//! |---|---|---|
//! | transmission angle of a loop | [`transmission_angle`], [`transmission_range`], [`Sampled::transmission`](crate::analysis::Sampled::transmission) | the angles of coupler and follower; its minimum located at roots of analogs |
//! | Grashof class, which link turns fully | [`grashof()`] | the four link lengths (closed form) |
//! | time (quick-return) ratio | [`time_ratio()`], [`Sampled::time_ratio`](crate::analysis::Sampled::time_ratio) | the located extremes of an output over one input turn |
//! | dead centres and limit positions | [`Limits`] | the sweep's events and the located extremes of output columns |
//!
//! Every metric is dimensionless or an angle: a mechanism in metres, millimetres or micrometres
//! gives the same values.

pub mod grashof;
pub mod limits;
pub mod time_ratio;
pub mod transmission;

pub use grashof::{FourBarLinks, Grashof, GrashofClass, Link, grashof};
pub use limits::{LimitReport, Limits, OutputLimits, limits_of};
pub use time_ratio::{TimeRatio, time_ratio};
pub use transmission::{AngleAt, TransmissionRange, transmission_angle, transmission_range};
