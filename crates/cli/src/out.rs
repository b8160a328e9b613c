//! Standard output that ends quietly on a closed pipe (`bipo run scene.toml | head`): `println!`
//! panics on a write error, and a reader that stops early is no error of the run. On
//! `BrokenPipe` the process exits with status 0, as a Unix tool killed by `SIGPIPE` stops
//! writing; any other write error is reported and exits with 1.

use std::io::{ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Whether this process prints nothing (the ranks other than 0 of a distributed run).
static SILENT: AtomicBool = AtomicBool::new(false);

/// From now on [`line`] writes nothing, and `bipo`'s errors are not printed: a distributed
/// run's ranks other than 0, so that each line and each scene error is printed once.
pub(crate) fn silence() {
    SILENT.store(true, Ordering::Relaxed);
}

/// Whether [`silence`] was called.
pub(crate) fn is_silent() -> bool {
    SILENT.load(Ordering::Relaxed)
}

/// Writes one line to standard output (see the module docs).
pub fn line(args: std::fmt::Arguments<'_>) {
    if is_silent() {
        return;
    }
    let mut out = std::io::stdout().lock();
    let written = out
        .write_fmt(args)
        .and_then(|()| out.write_all(b"\n"))
        .and_then(|()| out.flush());
    if let Err(e) = written {
        if e.kind() == ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        eprintln!("error: cannot write to standard output: {e}");
        std::process::exit(1);
    }
}

/// `println!` through [`line`].
macro_rules! outln {
    () => {
        $crate::out::line(format_args!(""))
    };
    ($($arg:tt)*) => {
        $crate::out::line(format_args!($($arg)*))
    };
}
pub(crate) use outln;
