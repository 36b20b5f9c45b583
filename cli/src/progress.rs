//! A progress bar on long work (`indicatif`): drawn on standard error, only when it is a
//! terminal and the work is long enough to watch, so that pipes, files and tests never see it.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// Samples from which a sweep's progress is shown: shorter sweeps of the shipped mechanisms
/// finish in a blink, where a bar would only flicker.
pub const MIN_SAMPLES: usize = 2000;

/// Starts from which a synthesis search's progress is shown: each is a local solve and a
/// verifying sweep, a few milliseconds; fewer finish within a second or two on all cores.
pub const MIN_STARTS: usize = 256;

/// A bar of `len` steps (samples, then columns) titled `what`, or a hidden one where standard
/// error is not a terminal or `samples` is below [`MIN_SAMPLES`].
pub fn bar(what: &str, len: usize, samples: usize) -> ProgressBar {
    bar_if(samples >= MIN_SAMPLES, what, len)
}

/// A bar of `len` steps titled `what` where the work is `long` and standard error is a
/// terminal; a hidden one otherwise.
pub fn bar_if(long: bool, what: &str, len: usize) -> ProgressBar {
    if !long || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len as u64), ProgressDrawTarget::stderr());
    // The template is a constant: it parses (a failure would only lose the bar's style).
    if let Ok(style) = ProgressStyle::with_template("{msg} [{wide_bar}] {pos}/{len} ({eta} left)") {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(what.to_string());
    bar
}
