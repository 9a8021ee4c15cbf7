//! What the command line prints when something fails: a diagnostic,
//! or why a job or a Pailou stopped, on standard error -> the exit code
//! (sysexits: 64 usage, 65 bad input, 66 missing input, 74 I/O error).

use miette::Diagnostic;

use super::{EX_DATAERR, EX_IOERR, EX_NOINPUT, EX_USAGE};
use crate::driver::{self, PailouError, Reason};

/// Prints one diagnostic, with colour when `color` is set.
pub(super) fn report(d: &dyn Diagnostic, color: bool) {
    eprint!("{}", driver::render_diagnostic(d, color));
}

/// Reports an output that was not written; the exit code (65 when the
/// exporter refused the model, 74 when the file could not be written).
pub(super) fn write_failed(reason: Reason, color: bool) -> i32 {
    match reason {
        Reason::Export(e) => {
            report(e.as_ref(), color);
            EX_DATAERR
        }
        Reason::Write { path, error } => {
            eprintln!("lsys: cannot write {}: {error}", path.display());
            EX_IOERR
        }
        Reason::Guided(e) => {
            report(e.as_ref(), color);
            EX_DATAERR
        }
        other => failed(other, "", color),
    }
}

/// Prints why a job failed; the exit code.
pub(super) fn failed(reason: Reason, name: &str, color: bool) -> i32 {
    match reason {
        Reason::Input(d) => {
            eprint!("{}", d.render(color));
            EX_NOINPUT
        }
        Reason::Grammar(d) => {
            let errors = d.error_count();
            eprint!("{}", d.render(color));
            eprintln!(
                "{}: {errors} error{}",
                name,
                if errors == 1 { "" } else { "s" }
            );
            EX_DATAERR
        }
        Reason::Build(e) => {
            report(e.as_ref(), color);
            EX_DATAERR
        }
        other => write_failed(other, color),
    }
}

/// Prints why a Pailou could not be read; the exit code.
pub(super) fn pailou_failed(e: PailouError, color: bool) -> i32 {
    match e {
        PailouError::Graph(e) => {
            report(e.as_ref(), color);
            EX_DATAERR
        }
        e @ PailouError::Read { .. } => {
            eprintln!("lsys: {e}");
            EX_NOINPUT
        }
        e @ PailouError::Style { .. } => {
            eprintln!("lsys: {e}");
            EX_USAGE
        }
    }
}
