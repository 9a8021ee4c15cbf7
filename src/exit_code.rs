//! Exit codes of the front ends (`lsys` and its REPL), from BSD's
//! sysexits: what a script calling `lsys` can tell apart.

pub const EX_OK: i32 = 0;
/// The command line was wrong.
pub const EX_USAGE: i32 = 64;
/// The grammar (or another input) has mistakes.
pub const EX_DATAERR: i32 = 65;
/// An input file could not be read.
pub const EX_NOINPUT: i32 = 66;
/// A bug in lsys (a panic).
pub const EX_SOFTWARE: i32 = 70;
/// The system refused a resource (a thread).
pub const EX_OSERR: i32 = 71;
/// An output could not be written.
pub const EX_IOERR: i32 = 74;
