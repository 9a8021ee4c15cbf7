//! `lsys repl [FILE]`: explore a grammar step by step. Input: lines typed
//! at a terminal (rustyline: history in the user's data directory, tab
//! completion, multi-line input, Ctrl-C to stop a derivation) or read from
//! a pipe (one input per line, plain output, so sessions can be scripted);
//! output: each input's reply on standard output, errors included, in
//! order.
//!
//! The REPL is a front end: what each command does to the grammar and its
//! derivation (load, step, edit, undo, inspect, export) is the driver's
//! [`crate::driver::session`], which names the stages; these files read
//! and print, and name only the driver and the API.
//!
//! * `execute.rs`: one input line to the session's reply;
//! * `commands.rs`: the table of `:commands` (dispatch, `:help`, completion);
//! * `input.rs`: continuation and classification of input lines;
//! * `complete.rs`: the line editor's completer and validator;
//! * `meter.rs`: the progress bar the session's long operations show.

mod commands;
mod complete;
mod execute;
mod input;
mod meter;

use std::io::{self, BufRead, IsTerminal, Write};
use std::path::PathBuf;
use std::sync::atomic::Ordering;

use rustyline::error::ReadlineError;
use rustyline::history::FileHistory;
use rustyline::{CompletionType, Editor};

pub use crate::driver::session::{Names, Reply, Session, Settings, Source};
pub use commands::{Arg, Command, COMMANDS};
pub use execute::execute;

use crate::exit_code::{EX_DATAERR, EX_IOERR, EX_OK};

/// How `lsys repl` was started.
#[derive(Clone, Debug, Default)]
pub struct Config {
    pub file: Option<String>,
    /// The step to derive to after loading `file`.
    pub step: u32,
    /// Seed and limits of derivations, and the `-D` overrides.
    pub options: crate::GrammarOptions,
    /// Print each piped input as `> input` before its reply.
    pub echo: bool,
    /// `--color always` / `never`; `None` decides by the terminal.
    pub color: Option<bool>,
}

/// Runs a session; the exit code (65 when piped input had an error).
pub fn run(cfg: Config) -> i32 {
    let interactive = io::stdin().is_terminal();
    let color = cfg.color.unwrap_or(
        interactive && io::stdout().is_terminal() && std::env::var_os("NO_COLOR").is_none(),
    );
    let mut session = Session::new(Settings {
        color,
        options: cfg.options.clone(),
    });
    if interactive {
        session.set_meters(Box::new(|| Box::new(meter::Bar::new())));
    }
    let mut failed = false;
    if interactive {
        println!(
            "lsys {}: `:help` lists the commands, Ctrl-D leaves",
            env!("CARGO_PKG_VERSION")
        );
    }
    if let Some(file) = &cfg.file {
        let reply = match session.start(file, cfg.step) {
            Ok(text) => Reply { text, ok: true },
            Err(text) => Reply { text, ok: false },
        };
        failed |= !reply.ok;
        if print(&reply.text).is_err() {
            return EX_OK;
        }
    }
    let code = if interactive {
        interactive_loop(&mut session)
    } else {
        piped_loop(&mut session, cfg.echo)
    };
    match code {
        Ok(f) if failed || f => EX_DATAERR,
        Ok(_) => EX_OK,
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => EX_OK,
        Err(e) => {
            eprintln!("lsys: {e}");
            EX_IOERR
        }
    }
}

/// Prints a reply (nothing for an empty one), ending it with a newline.
fn print(text: &str) -> io::Result<()> {
    if text.is_empty() {
        return Ok(());
    }
    let mut out = io::stdout().lock();
    out.write_all(text.as_bytes())?;
    if !text.ends_with('\n') {
        out.write_all(b"\n")?;
    }
    out.flush()
}

/// Where the history is kept: `lsys/history.txt` in the user's data
/// directory (none without one).
fn history_path() -> Option<PathBuf> {
    dirs::data_dir().map(|d| d.join("lsys").join("history.txt"))
}

/// The terminal: rustyline, until Ctrl-D or `:quit`. Returns whether
/// any input failed (always `false`: at a terminal that is no error).
fn interactive_loop(session: &mut Session) -> io::Result<bool> {
    let flag = session.interrupt_flag();
    // Outside `readline` the terminal is not raw: Ctrl-C is a signal, and
    // the derivation checks the flag between steps.
    let _ = ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst));
    let config = rustyline::Config::builder()
        .completion_type(CompletionType::List)
        .auto_add_history(false)
        .build();
    let mut ed: Editor<complete::Helper, FileHistory> =
        Editor::with_config(config).map_err(io::Error::other)?;
    ed.set_helper(Some(complete::Helper::new()));
    let history = history_path();
    if let Some(h) = &history {
        let _ = ed.load_history(h);
    }
    loop {
        if let Some(h) = ed.helper_mut() {
            h.names = session.names();
        }
        match ed.readline(&session.prompt()) {
            Ok(line) => {
                if !line.trim().is_empty() {
                    let _ = ed.add_history_entry(line.as_str());
                }
                let reply = execute(session, &line);
                print(&reply.text)?;
                if session.quit_requested() {
                    break;
                }
            }
            // Ctrl-C at the prompt drops the line being typed.
            Err(ReadlineError::Interrupted) => continue,
            Err(ReadlineError::Eof) => break,
            Err(e) => {
                eprintln!("lsys: {e}");
                break;
            }
        }
    }
    if let Some(h) = &history {
        if let Some(dir) = h.parent() {
            let _ = std::fs::create_dir_all(dir);
        }
        let _ = ed.save_history(h);
    }
    Ok(false)
}

/// A pipe or file: one input per line (more while brackets are open).
/// Returns whether any input failed.
fn piped_loop(session: &mut Session, echo: bool) -> io::Result<bool> {
    let mut failed = false;
    let mut pending = String::new();
    let mut lines = io::stdin().lock().lines();
    loop {
        let line = lines.next().transpose()?;
        let Some(line) = line else { break };
        if !pending.is_empty() {
            pending.push('\n');
        }
        pending.push_str(&line);
        if input::needs_more(&pending) {
            continue;
        }
        failed |= !run_piped(session, &std::mem::take(&mut pending), echo)?;
        if session.quit_requested() {
            return Ok(failed);
        }
    }
    if !pending.is_empty() {
        failed |= !run_piped(session, &pending, echo)?;
    }
    Ok(failed)
}

fn run_piped(session: &mut Session, input: &str, echo: bool) -> io::Result<bool> {
    if echo && !input.trim().is_empty() {
        let mut shown = String::new();
        for (i, l) in input.lines().enumerate() {
            shown.push_str(if i == 0 { "> " } else { ". " });
            shown.push_str(l);
            shown.push('\n');
        }
        print(&shown)?;
    }
    let reply = execute(session, input);
    print(&reply.text)?;
    Ok(reply.ok)
}
