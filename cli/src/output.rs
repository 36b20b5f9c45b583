//! Standard output, written so that a write that fails (a full disk, a reader gone) is
//! reported: a message on standard error and exit code 74, never a panic and never a success.
//! Every write is flushed before it counts as done: a byte left in the buffer at exit would be
//! lost without an error.

use crate::{Failed, exit};
use kinloop_runtime::Table;
use std::io::Write;

/// The failure of a write of `what` to standard output: its message on standard error,
/// [`exit::IO_ERR`].
pub fn failed(what: &str, e: std::io::Error) -> Failed {
    eprintln!("error: cannot write {what}: {e}");
    Failed(exit::IO_ERR)
}

/// Writes `text` (`what`: "the report") to standard output and flushes it.
pub fn text(text: &str, what: &str) -> Result<(), Failed> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes()).and_then(|()| out.flush()).map_err(|e| failed(what, e))
}

/// Writes `table` as CSV (`what`: "the table") to standard output and flushes it.
pub fn table(table: &Table, what: &str) -> Result<(), Failed> {
    let mut out = std::io::stdout().lock();
    table.write_csv(&mut out).and_then(|()| out.flush()).map_err(|e| failed(what, e))
}

/// What the command line's parser stopped at, written where it goes, and the exit code: the
/// help and the version on standard output (0, or [`exit::IO_ERR`] with a message where it
/// cannot be written: clap's own `exit` lets that failure go and succeeds), a usage error on
/// standard error ([`exit::USAGE`]; a failure to write that is let go, as every message on
/// standard error is).
pub fn parser_stop(e: &clap::Error) -> u8 {
    let printed = e.print().and_then(|()| std::io::stdout().flush());
    match printed {
        Err(io) if !e.use_stderr() => {
            let what = if e.kind() == clap::error::ErrorKind::DisplayVersion { "the version" } else { "the help" };
            failed(what, io).0
        }
        _ => u8::try_from(e.exit_code()).unwrap_or(exit::USAGE),
    }
}
