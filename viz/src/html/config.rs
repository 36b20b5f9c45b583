//! What an interactive page shows: its title, the readouts (and their charts), how it plays.

use super::HtmlError;
use crate::draw::{MAX_SECONDS, MIN_SECONDS, Scalar};
use crate::plot::Kind;
use kinloop_runtime::ColumnKey;

/// Where a readout's value comes from.
#[derive(Clone, Debug)]
pub enum Value {
    /// An input, unknown or output column of the mechanism, by name (`"phi"`, `"gamma"`,
    /// `"p.x"`): a typed column `Name::COL.gamma` or a string.
    Column(String),
    /// An expression of the state (a transmission angle, a distance between two points).
    Expr(Scalar),
}

/// One live value of the page: shown beside the drawing with its unit as the slider moves
/// (angles in degrees), and, unless turned off, charted against the input with a cursor that
/// follows the slider.
///
/// The value is shown to a hundredth of a degree for an angle, else to five significant
/// digits of its largest value over the motion, with decimals for ordinary magnitudes
/// (`"-0.0123"`, `"1.2345"`) and with a power of ten for tiny or huge ones (a largest value
/// below about 1e-4 or from 1e5: `"-5.661e-7"`, `"1.5896e9"`), as the charts' axes are
/// labelled. Values far from zero that vary little over the motion (an input after many
/// turns) keep at least three significant digits of their span, so that the frames differ.
#[derive(Clone, Debug)]
pub struct Readout {
    /// Where the value comes from.
    pub value: Value,
    /// What the page calls it (the column's name when not given).
    pub label: Option<String>,
    /// The quantity kind, which fixes the unit and how the value is shown (the mechanism's
    /// inferred kind of the column when not given: angles in degrees, lengths in
    /// [`HtmlConfig::length_unit`]).
    pub kind: Option<Kind>,
    /// Draw a chart of the value against the input.
    pub chart: bool,
}

impl Readout {
    /// The column `col` of the mechanism: an input, an unknown or an output column.
    pub fn column(col: impl ColumnKey) -> Readout {
        Readout { value: Value::Column(col.column_name().to_string()), label: None, kind: None, chart: true }
    }

    /// A value computed from the state, called `label`, of quantity `kind` (given in the
    /// library's units: radians for an angle).
    pub fn expr(label: &str, kind: Kind, f: impl Fn(&crate::draw::StateRef) -> f64 + Send + Sync + 'static) -> Readout {
        Readout { value: Value::Expr(Scalar::expr(f)), label: Some(label.to_string()), kind: Some(kind), chart: true }
    }

    /// Shown as `label`.
    pub fn label(mut self, label: &str) -> Readout {
        self.label = Some(label.to_string());
        self
    }

    /// Of quantity `kind` (its unit and how it is shown).
    pub fn kind(mut self, kind: Kind) -> Readout {
        self.kind = Some(kind);
        self
    }

    /// Shown as a number only, without a chart.
    pub fn without_chart(mut self) -> Readout {
        self.chart = false;
        self
    }
}

/// How [`html`](super::html) builds its page: title, readouts, playing.
///
/// Every input of the mechanism always has a readout (a readout naming an input replaces
/// its default one, e.g. to give a time input its unit); the readouts added here follow.
#[derive(Clone, Debug)]
pub struct HtmlConfig {
    /// The page's title (and heading).
    pub title: String,
    /// Readouts besides the inputs', in order.
    pub readouts: Vec<Readout>,
    /// The unit of the mechanism's lengths, written after length readouts and on the charts'
    /// axes (default `"length unit"`, as in tables). Left at the default, a page takes the
    /// drawing's own unit where it has one ([`Drawing::length_unit`](crate::draw::Drawing::length_unit),
    /// its scale bar's): one unit given once.
    pub length_unit: String,
    /// Duration of one pass of the motion when playing, in seconds (default 6), from a
    /// millisecond to a billion seconds, as an animation's.
    pub seconds: f64,
    /// Play forward then backward (a motion that stops at a limit position, where the real
    /// mechanism turns back), rather than starting again (a full turn). Default `false`.
    pub back_and_forth: bool,
    /// Start playing when the page opens (default `true`; a page opened with a pose in its
    /// address, `page.html#i=40`, shows that pose and waits).
    pub autoplay: bool,
    /// Largest number of poses written (in equal steps along the motion, first and last kept,
    /// only the step to the last shorter; default 721). The size of the page grows with it. A grid's page
    /// ([`html_grid`](super::html_grid)) writes every cell: a grid of more cells is an error.
    pub max_frames: usize,
    /// Width and height of each chart in pixels (default 380 x 170).
    pub chart_size: [f64; 2],
}

impl Default for HtmlConfig {
    fn default() -> Self {
        HtmlConfig {
            title: "Mechanism".to_string(),
            readouts: Vec::new(),
            length_unit: kinloop_runtime::LENGTH_UNIT.to_string(),
            seconds: 6.0,
            back_and_forth: false,
            autoplay: true,
            max_frames: 721,
            chart_size: [380.0, 170.0],
        }
    }
}

impl HtmlConfig {
    /// A page called `title`, with the defaults otherwise.
    pub fn new(title: &str) -> HtmlConfig {
        HtmlConfig { title: title.to_string(), ..HtmlConfig::default() }
    }

    /// Adds a readout (and chart) of column `col` (an input, unknown or output column:
    /// `Name::COL.gamma`, `"p.x"`), labelled with its name, of the mechanism's inferred kind.
    pub fn show(mut self, col: impl ColumnKey) -> HtmlConfig {
        self.readouts.push(Readout::column(col));
        self
    }

    /// Adds `readout`.
    pub fn with_readout(mut self, readout: Readout) -> HtmlConfig {
        self.readouts.push(readout);
        self
    }

    /// Sets the unit written after lengths (the page's, whatever the drawing's).
    pub fn with_length_unit(mut self, unit: &str) -> HtmlConfig {
        self.length_unit = unit.to_string();
        self
    }

    /// The unit of the page's lengths over `drawing`: [`HtmlConfig::length_unit`] where it is not
    /// the default, else the drawing's where it has one. A drawing given `mm` had its page in
    /// "length unit" unless the page was given `mm` too.
    pub(crate) fn length_unit_of<'a>(&'a self, drawing: &'a crate::draw::Drawing) -> &'a str {
        match drawing.length_unit.as_deref() {
            Some(unit) if self.length_unit == kinloop_runtime::LENGTH_UNIT => unit,
            _ => &self.length_unit,
        }
    }

    /// Sets the duration of one pass, in seconds.
    pub fn with_seconds(mut self, seconds: f64) -> HtmlConfig {
        self.seconds = seconds;
        self
    }

    /// Plays forward then backward (`true`) or starts each pass again (`false`).
    pub fn with_back_and_forth(mut self, back_and_forth: bool) -> HtmlConfig {
        self.back_and_forth = back_and_forth;
        self
    }

    /// Starts playing when the page opens, or not.
    pub fn with_autoplay(mut self, autoplay: bool) -> HtmlConfig {
        self.autoplay = autoplay;
        self
    }

    /// Sets the largest number of poses written.
    pub fn with_max_frames(mut self, frames: usize) -> HtmlConfig {
        self.max_frames = frames;
        self
    }

    /// Sets the size of each chart in pixels.
    pub fn with_chart_size(mut self, width: f64, height: f64) -> HtmlConfig {
        self.chart_size = [width, height];
        self
    }

    /// Every setting within its range.
    pub(crate) fn check(&self) -> Result<(), HtmlError> {
        let bad = |s: String| Err(HtmlError::InvalidSetting(s));
        if self.max_frames < 2 {
            return bad(format!("a page needs at least 2 frames, not {}", self.max_frames));
        }
        // As an animated SVG's: the page's script divides the time played by the duration,
        // and a duration of a few subnormal seconds makes that infinite (no pose to show).
        if !(MIN_SECONDS..=MAX_SECONDS).contains(&self.seconds) {
            return bad(format!("duration {} s must be from {MIN_SECONDS} s to {MAX_SECONDS:e} s", self.seconds));
        }
        let [w, h] = self.chart_size;
        if !(w.is_finite() && h.is_finite() && (120.0..=4000.0).contains(&w) && (80.0..=4000.0).contains(&h)) {
            return bad(format!("chart size {w} x {h} must be 120..4000 x 80..4000 pixels"));
        }
        Ok(())
    }
}
