//! Standard output, written so that a write that fails (a full disk, a reader gone) is
//! reported: a message on standard error and exit code 74, never a panic and never a success.
//! Every write is flushed before it counts as done: a byte left in the buffer at exit would be
//! lost without an error.

use crate::{Failed, exit};
use kinloop_runtime::Table;
use std::io::Write;
use std::path::Path;

/// The failure of a write of `what` to standard output: its message on standard error,
/// [`exit::IO_ERR`].
pub fn failed(what: &str, e: std::io::Error) -> Failed {
    eprintln!("error: cannot write {what}: {e}");
    Failed(exit::IO_ERR)
}

/// A file named by an option (`--events`, `--plot`, `--flywheel`), opened before the work that
/// fills it, so that a path that cannot be written stops the command first. What was at the
/// path is not touched until there is something to write: a file that existed keeps its
/// content if the command fails, and only a file the command made itself is removed again
/// ([`OutFile::abandon`]). Removing the path given, whatever it was, deleted a user's file (and,
/// run as root, a device: `--plot /dev/null`) on a typo in another option. Once the writing
/// has begun, a write that fails removes a regular file whoever made it ([`OutFile::write`]).
pub struct OutFile {
    file: std::fs::File,
    path: std::path::PathBuf,
    /// Nothing was at the path: the command made the file.
    made: bool,
}

/// The file at `path` opened for writing (`None` where none was asked), before anything is
/// computed: made where nothing is there, else opened as it is, without emptying it. Its
/// failure says `what` (`"the events file"`) and the path, [`exit::CANT_CREATE`].
pub fn created(path: Option<&std::path::Path>, what: &str) -> Result<Option<OutFile>, Failed> {
    let Some(path) = path else { return Ok(None) };
    let cannot = |e: std::io::Error| {
        eprintln!("error: cannot create {what} {}: {e}", path.display());
        Failed(exit::CANT_CREATE)
    };
    // Made new, or else opened as it is: one test of what is there, no window between them.
    let opened = std::fs::OpenOptions::new().write(true).create_new(true).open(path);
    let (file, made) = match opened {
        Ok(file) => (file, true),
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
            (std::fs::OpenOptions::new().write(true).open(path).map_err(cannot)?, false)
        }
        Err(e) => return Err(cannot(e)),
    };
    Ok(Some(OutFile { file, path: path.to_path_buf(), made }))
}

impl OutFile {
    /// The file to write into, emptied first where it is a regular file: what it held is
    /// replaced only now that the command has something to write (a device, `/dev/null`, is
    /// written as it is).
    pub fn into_file(self) -> std::io::Result<std::fs::File> {
        if self.file.metadata()?.is_file() {
            self.file.set_len(0)?;
        }
        Ok(self.file)
    }

    /// Writes `what` (`"the events"`) into the file with `write`, the file made ready first
    /// ([`OutFile::into_file`]). A write that fails part way (a full disk, a file size limit)
    /// removes the file where it is a regular file, rather than leave it cut short: what it
    /// held was replaced when the writing began, and a table cut short reads as a shorter one.
    pub fn write(self, what: &str, write: impl FnOnce(std::fs::File) -> std::io::Result<()>) -> Result<(), Failed> {
        let path = self.path.clone();
        let regular = self.file.metadata().is_ok_and(|m| m.is_file());
        self.into_file().and_then(write).map_err(|e| {
            if regular {
                let _ = std::fs::remove_file(&path);
            }
            failed(what, e)
        })
    }

    /// The command failed before writing: the file removed where the command made it (best
    /// effort: the error reported is the one that stopped the command); what was at the path
    /// before is left as it was.
    pub fn abandon(self) {
        let OutFile { file, path, made } = self;
        drop(file);
        if made {
            let _ = std::fs::remove_file(path);
        }
    }
}

/// Refuses a file to write that is one the command reads (`kinloop dynamics engine.kl
/// --flywheel engine.kl`, or the same file by another path or a link): the command would
/// replace its own declaration with its output. A usage error ([`exit::USAGE`]) naming the
/// option, before anything is read or written.
pub fn not_read(read: &[&Path], written: &[(&str, &Path)]) -> Result<(), Failed> {
    for &(option, out) in written {
        if let Some(input) = read.iter().find(|input| same_file(input, out)) {
            eprintln!(
                "error: {option} {} is the file read, {}: writing it would replace it; name another file",
                out.display(),
                input.display()
            );
            return Err(Failed(exit::USAGE));
        }
    }
    Ok(())
}

/// Refuses `-` as a file to write (`--events -`, `--flywheel -`, `--plot -`): by the usual
/// convention, and `animate --out -`'s, it names standard output, which holds the command's
/// table here, and it made a file named `-` in the working directory without a word. A usage
/// error ([`exit::USAGE`]) naming the option and what to write instead, before anything is
/// written. `written` holds no `--out -` (it is standard output, not a file: see `main`).
pub fn not_dash(written: &[(&str, &Path)]) -> Result<(), Failed> {
    match written.iter().find(|(_, out)| out.as_os_str() == "-") {
        Some((option, _)) => Err(exit::usage(format!(
            "{option} - would be standard output, which the command's own output goes to: name a file (`./-` for a \
             file named `-`)"
        ))),
        None => Ok(()),
    }
}

/// Refuses a file to write that standard output is redirected to (`kinloop sweep four_bar.kl
/// --events out.csv > out.csv`): the table written to standard output and the file written by
/// the option would overwrite each other's bytes, and the command would succeed with neither
/// whole. A usage error ([`exit::USAGE`]) naming the option, before anything is written. Only
/// where standard output is a regular file (a terminal, pipe or `/dev/null` is no file to lose).
pub fn not_standard_output(written: &[(&str, &Path)]) -> Result<(), Failed> {
    let Some(stdout) = standard_output_file() else { return Ok(()) };
    for &(option, out) in written {
        if std::fs::metadata(out).is_ok_and(|m| m.is_file() && same_inode(&m, &stdout)) {
            eprintln!(
                "error: {option} {} is the file standard output is redirected to: the two would overwrite \
                 each other; name another file, or redirect standard output elsewhere",
                out.display()
            );
            return Err(Failed(exit::USAGE));
        }
    }
    Ok(())
}

/// The metadata of the regular file standard output is redirected to, if it is one (on systems
/// that tell a file by its device and inode).
fn standard_output_file() -> Option<std::fs::Metadata> {
    #[cfg(unix)]
    {
        use std::os::fd::AsFd;
        let fd = std::io::stdout().as_fd().try_clone_to_owned().ok()?;
        std::fs::File::from(fd).metadata().ok().filter(std::fs::Metadata::is_file)
    }
    #[cfg(not(unix))]
    {
        None
    }
}

/// Whether two regular files' metadata are of one file (the same device and inode); `false`
/// where the system does not tell.
fn same_inode(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        (a.dev(), a.ino()) == (b.dev(), b.ino())
    }
    #[cfg(not(unix))]
    {
        let _ = (a, b);
        false
    }
}

/// Whether `a` and `b` are the same regular file (the same device and inode where the system
/// has them, else the same canonical path): `false` where either is missing or not a regular
/// file (a device such as `/dev/null` may be read and written alike).
fn same_file(a: &Path, b: &Path) -> bool {
    let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) else { return false };
    if !(ma.is_file() && mb.is_file()) {
        return false;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        (ma.dev(), ma.ino()) == (mb.dev(), mb.ino())
    }
    #[cfg(not(unix))]
    {
        matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
    }
}

/// Writes `what` (`"the events"`) with `write`: into `file` where one was asked
/// ([`OutFile::write`]), else `write` is given `None` (it writes to standard error).
pub fn write_into(
    file: Option<OutFile>,
    what: &str,
    write: impl FnOnce(Option<std::fs::File>) -> std::io::Result<()>,
) -> Result<(), Failed> {
    match file {
        Some(file) => file.write(what, |file| write(Some(file))),
        None => write(None).map_err(|e| failed(what, e)),
    }
}

/// Writes `text` (`what`: "the report") to standard output and flushes it.
pub fn text(text: &str, what: &str) -> Result<(), Failed> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes()).and_then(|()| out.flush()).map_err(|e| failed(what, e))
}

/// Writes `table` as CSV (`what`: "the table") to standard output and flushes it, a zero
/// written without a sign ([`crate::csv_rows`]).
pub fn table(table: &Table, what: &str) -> Result<(), Failed> {
    let out = std::io::BufWriter::new(std::io::stdout().lock());
    crate::csv_rows::write_table(out, table).map_err(|e| failed(what, e))
}

/// What the command line's parser stopped at, written where it goes, and the exit code: the
/// help and the version on standard output (0, or [`exit::IO_ERR`] with a message where it
/// cannot be written: clap's own `exit` lets that failure go and succeeds), a usage error on
/// standard error ([`exit::USAGE`]; a failure to write that is let go, as every message on
/// standard error is).
/// `closed` is [`stdout_closed`] at start-up: std's writes to a closed standard output succeed
/// and write nothing.
pub fn parser_stop(e: &clap::Error, closed: bool) -> u8 {
    let printed = match closed {
        true => Err(closed_error()),
        false => e.print().and_then(|()| std::io::stdout().flush()),
    };
    match printed {
        Err(io) if !e.use_stderr() => {
            let what = if e.kind() == clap::error::ErrorKind::DisplayVersion { "the version" } else { "the help" };
            failed(what, io).0
        }
        _ => u8::try_from(e.exit_code()).unwrap_or(exit::USAGE),
    }
}

/// Whether standard output was closed when the process started (`kinloop ... >&-`: no file
/// descriptor 1); found before `main` by [`find_closed_stdout`].
#[cfg(target_os = "linux")]
static STDOUT_CLOSED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

// Std's start-up, before `main`, opens `/dev/null` (read-write) on a standard descriptor it finds
// closed, so that a file opened later does not take its place: by `main` a closed standard
// output is that `/dev/null`, its writes succeed and the whole output is lost with exit code 0,
// and it cannot be told from a `/dev/null` given on purpose the same way (Python's
// `subprocess.DEVNULL`, systemd's `StandardOutput=null`). So the descriptor is looked at
// earlier: a function in `.init_array` runs before std's start-up (std captures the arguments
// the same way).
#[cfg(target_os = "linux")]
#[used]
#[unsafe(link_section = ".init_array")]
static FIND_CLOSED_STDOUT: extern "C" fn() = find_closed_stdout;

/// Records in [`STDOUT_CLOSED`] whether descriptor 1 is open, by its entry in `/proc/self/fd`
/// (a `stat`, no descriptor opened); without `/proc` mounted it counts as open.
#[cfg(target_os = "linux")]
extern "C" fn find_closed_stdout() {
    let listed = std::fs::symlink_metadata("/proc/self/fd").is_ok();
    let missing = std::fs::symlink_metadata("/proc/self/fd/1").is_err_and(|e| e.kind() == std::io::ErrorKind::NotFound);
    STDOUT_CLOSED.store(listed && missing, std::sync::atomic::Ordering::Relaxed);
}

/// Whether standard output was closed when `kinloop` started (`kinloop ... >&-`), where its
/// output would be lost without an error (see [`FIND_CLOSED_STDOUT`]).
#[cfg(target_os = "linux")]
pub fn stdout_closed() -> bool {
    STDOUT_CLOSED.load(std::sync::atomic::Ordering::Relaxed)
}

/// Whether standard output was closed when `kinloop` started: not known on this system (std's
/// start-up has put `/dev/null` in its place by `main`), so taken as open.
#[cfg(not(target_os = "linux"))]
pub fn stdout_closed() -> bool {
    false
}

/// The failure to write to a closed standard output, saying what to give instead.
pub fn closed_error() -> std::io::Error {
    std::io::Error::other(
        "standard output is closed: give kinloop one to write to (a file, a pipe, or >/dev/null to discard it)",
    )
}

/// A unit written after a number in a message: ` deg`, or nothing for a quantity without one,
/// a pure number's `1` included (a table's header writes `h [1]`, but "stands still at 0 1"
/// read as two numbers).
pub fn unit_suffix(unit: &str) -> String {
    if unit.is_empty() || unit == "1" { String::new() } else { format!(" {unit}") }
}

#[cfg(test)]
mod tests {
    use super::unit_suffix;

    /// A unit follows its number after a space; a pure number's `1` is not written after one.
    #[test]
    fn a_pure_number_has_no_unit_after_it() {
        assert_eq!(unit_suffix("deg"), " deg");
        assert_eq!(unit_suffix("length unit"), " length unit");
        assert_eq!(unit_suffix("1"), "");
        assert_eq!(unit_suffix(""), "");
    }
}
