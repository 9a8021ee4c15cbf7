//! The command line: arguments -> a command run against the library ->
//! an exit code from sysexits (64 usage, 65 bad input, 66 missing input,
//! 70 internal error, 71 no thread, 74 I/O error).

mod args;
mod batch;
mod commands;
mod guided;
mod model;
mod options;
mod report;
#[cfg(feature = "studio")]
mod studio;
mod watch;

use std::io::IsTerminal;

use clap::Parser;

pub use args::{Cli, Command};

pub use crate::exit_code::*;

/// Runs the command line of this process and returns its exit code.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { EX_USAGE } else { EX_OK };
            let _ = e.print();
            return code;
        }
    };
    let color = match cli.color {
        args::Color::Always => true,
        args::Color::Never => false,
        args::Color::Auto => {
            std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none()
        }
    };
    // A panic is a bug in lsys, never the user's fault: say so and exit 70.
    std::panic::set_hook(Box::new(|info| {
        eprintln!("lsys: internal error: {info}\nThis is a bug in lsys; please report it with the input that caused it.");
    }));
    let repl_color = match cli.color {
        args::Color::Always => Some(true),
        args::Color::Never => Some(false),
        args::Color::Auto => None,
    };
    // All the work runs on the worker thread below, and glibc gives a
    // thread other than the first an arena of its own, which it grows a
    // page at a time, one `mprotect` call each (228 calls for a Pailou, a
    // tenth of its time). One arena grows by `brk` with 128 KiB to spare.
    // Not for `lsys batch --jobs K`: its K builders would take turns at
    // the one arena's lock (200 small models with --jobs 2 on two cores:
    // 1.04 s with one arena, 0.88 s with an arena each).
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    if !matches!(&cli.command, Command::Batch(b) if b.jobs > 1) {
        // SAFETY: mallopt only changes the allocator's settings; no other
        // thread has started yet.
        unsafe {
            libc::mallopt(libc::M_ARENA_MAX, 1);
        }
    }
    // The compiler's recursive parts (the PEG, the Pratt parser, resolve,
    // folding) get a deep stack; the parser refuses input deeper than they
    // can take with it (parse::MAX_NESTING, parse::MAX_OPERATORS).
    let worker = std::thread::Builder::new()
        .name("lsys".into())
        .stack_size(crate::driver::WORKER_STACK)
        .spawn(move || commands::run(&cli.command, color, repl_color));
    match worker.map(|w| w.join()) {
        Ok(Ok(code)) => code,
        Ok(Err(_)) => EX_SOFTWARE,
        Err(e) => {
            eprintln!("lsys: cannot start: {e}");
            EX_SOFTWARE
        }
    }
}
