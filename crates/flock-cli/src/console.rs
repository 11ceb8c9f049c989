//! Lines for the terminal that a closed pipe cannot turn into a panic.
//!
//! `flocking validate X.ron | head -1` closes standard output after one line, and `println!` would
//! then panic ("failed printing to stdout: Broken pipe"). [`outln!`](crate::outln),
//! [`out!`](crate::out) and [`errln!`](crate::errln) write through the locked stream instead and
//! drop what a reader that has gone can no longer read: the command finishes its work (a run still
//! writes and moves its files into place) and keeps its exit code. Any other error of the stream
//! (a full disk behind a redirection) is said once on standard error, if that is still open.

use std::fmt;
use std::io::{self, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Whether a failure of standard output was already said.
static SAID: AtomicBool = AtomicBool::new(false);

/// Writes `args` to standard output.
pub fn out(args: fmt::Arguments<'_>) {
    if let Err(e) = write(&mut io::stdout().lock(), args)
        && !SAID.swap(true, Ordering::Relaxed)
    {
        err(format_args!("warning: writing to standard output: {e}\n"));
    }
}

/// Whether writing to standard output failed (other than by a closed pipe): the command's exit
/// code is then not 0 (issue 27: `flocking validate s > /dev/full` exited 0).
#[must_use]
pub fn stdout_failed() -> bool {
    SAID.load(Ordering::Relaxed)
}

/// Writes `args` to standard error.
pub fn err(args: fmt::Arguments<'_>) {
    // nowhere is left to say that standard error failed
    let _ = write(&mut io::stderr().lock(), args);
}

/// Writes and flushes `args`; a closed pipe is not an error.
fn write(stream: &mut impl Write, args: fmt::Arguments<'_>) -> io::Result<()> {
    match stream.write_fmt(args).and_then(|()| stream.flush()) {
        Err(e) if e.kind() != io::ErrorKind::BrokenPipe => Err(e),
        _ => Ok(()),
    }
}

/// `println!` that a closed standard output cannot make panic ([`console`](crate::console)).
#[macro_export]
macro_rules! outln {
    () => {
        $crate::console::out(format_args!("\n"))
    };
    ($($arg:tt)*) => {
        $crate::console::out(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `print!` that a closed standard output cannot make panic ([`console`](crate::console)).
#[macro_export]
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::console::out(format_args!($($arg)*))
    };
}

/// `eprintln!` that a closed standard error cannot make panic ([`console`](crate::console)).
#[macro_export]
macro_rules! errln {
    ($($arg:tt)*) => {
        $crate::console::err(format_args!("{}\n", format_args!($($arg)*)))
    };
}
