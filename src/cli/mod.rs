//! The command line: arguments -> a command run against the library ->
//! an exit code from sysexits (64 usage, 65 bad input, 66 missing input,
//! 70 internal error, 71 no thread, 74 I/O error).

mod args;
mod batch;
mod commands;
mod guided;
mod infer;
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
    // SIGINT, SIGTERM and SIGHUP while an output is being written would
    // leave its temporary file behind: they are taken by a thread that
    // removes the temporaries, then exits as the signal would have (128 +
    // its number). Not for the REPL, whose Ctrl-C stops a derivation and
    // goes on, nor the language server, which an editor stops.
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    if !matches!(&cli.command, Command::Repl(_) | Command::Lsp(_)) {
        clean_up_on_signals();
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

/// Blocks SIGINT, SIGTERM and SIGHUP in this thread and every thread it
/// starts later, and starts a thread that waits for them: on one, it
/// deletes the temporary files of the outputs being written and exits
/// with 128 + the signal's number (130 for Ctrl-C, 143 for SIGTERM).
/// Waiting in a thread (not a signal handler) may lock and delete files
/// safely. Child processes get the default mask back (std resets it).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn clean_up_on_signals() {
    // SAFETY: plain libc calls on a local signal set; called before any
    // other thread starts, so every later thread inherits the mask.
    let set = unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for sig in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            libc::sigaddset(&mut set, sig);
        }
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return;
        }
        set
    };
    let started = std::thread::Builder::new()
        .name("lsys-signals".into())
        .spawn(move || {
            let mut sig = 0;
            // SAFETY: `set` is a valid signal set, `sig` a valid out pointer.
            if unsafe { libc::sigwait(&set, &mut sig) } == 0 {
                crate::driver::remove_temporaries();
                std::process::exit(128 + sig);
            }
        });
    if started.is_err() {
        // No thread to take them: let the signals act as before.
        // SAFETY: as above.
        unsafe {
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
        }
    }
}
