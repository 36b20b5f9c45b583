//! Closed-form four-bar synthesis from the classical theory: exact answers where the theory
//! gives them, and starting points for a general search.
//!
//! * **Function generation** ([`freudenstein()`]): input and output angles to be reached
//!   together (precision points, e.g. at [`chebyshev_points`] over the range of a function
//!   mapped onto angles by a [`FunctionMap`]) give the link lengths through Freudenstein's
//!   equation, exactly for three points and in the least-squares sense for more;
//!   [`structural_error`] analyses the result between the points.
//! * **Motion generation** ([`center_point_curve`], [`burmester_points`]): poses of a body (a
//!   point and an angle) give the dyads (a fixed pivot and a moving pivot on the body) that
//!   guide it through them: a one-parameter family for four poses (Burmester's center-point
//!   and circle-point curves), at most four for five (the Burmester points). Two such dyads
//!   make a four-bar whose coupler takes the poses.
//! * **As seeds** ([`FourBar`]): a function generator or two dyads as a whole four-bar (pivots,
//!   lengths, coupler point, link angles at every point), to map onto a declared four-bar's
//!   parameters and start the general search from
//!   ([`Search::with_seeds`](crate::synthesis::Search::with_seeds)).
//! * **Cognates** ([`cognates()`]): the two other four-bars whose coupler points trace the same
//!   curve as a four-bar's (the Roberts–Chebyshev theorem), for a path found with pivots or a
//!   transmission that do not suit.
//!
//! Every function is pure, takes plain numbers, and reports unusable input as a
//! [`ClassicalError`] (which converts into [`crate::Error`]). Angles are in radians,
//! counter-clockwise positive; lengths in any one unit (the tolerances are relative to the
//! problem's size). The theory, its conventions and how the results are verified are written
//! out in `docs/synthesis-classical.md`.

mod burmester;
mod chebyshev;
mod cognates;
mod compatibility;
mod dyad;
mod error;
mod four_bar;
mod freudenstein;
mod function_map;
mod position;
mod structural;

pub use burmester::{
    BurmesterConfig, BurmesterCurve, BurmesterPoints, CurvePoint, burmester_points, center_point_curve,
};
pub use chebyshev::chebyshev_points;
pub use cognates::cognates;
pub use dyad::{Dyad, Pose};
pub use error::ClassicalError;
pub use four_bar::FourBar;
pub use freudenstein::{COINCIDENT_ANGLE, FunctionGenerator, MIN_RCOND, PrecisionPoint, freudenstein};
pub use function_map::FunctionMap;
pub use position::Closure;
pub use structural::{StructuralError, structural_error};
