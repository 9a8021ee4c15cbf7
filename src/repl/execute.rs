//! One input line of the REPL -> the session's reply: the line is read as
//! a `:command` (found in [`super::commands`]), a production or `Axiom:`
//! statement, or a module string to rewrite once, and handed to the
//! driver's session as a [`Typed`]. Input: a line as typed; output: a
//! [`Reply`].

use super::commands;
use super::input::{self, Kind};
use crate::driver::session::{Reply, Session, Typed};

/// Runs one input: a `:command`, a production, `Axiom: ...`, or a module
/// string. A line that starts with blanks right after a production
/// continues it (as a successor continues in a file).
pub fn execute(session: &mut Session, line: &str) -> Reply {
    let continues =
        line.starts_with([' ', '\t']) && !input::is_statement(line) && !line.trim().is_empty();
    let text = match (session.last_production(), continues) {
        (Some(prev), true) => format!("{prev}\n{}", line.trim_end()),
        _ => indent_continuations(line.trim()),
    };
    let typed = match input::classify(&text) {
        Kind::Empty => Typed::Empty,
        Kind::Command { name, args } => match commands::find(name) {
            Ok(c) => Typed::Command {
                name: c.name,
                run: c.run,
                args,
            },
            Err(why) => Typed::Unknown(why),
        },
        Kind::Statement => Typed::Statement,
        Kind::Modules => Typed::Modules,
    };
    session.run_input(&text, typed)
}

/// Lines after the first indented, so that input continued inside
/// brackets reads as a successor continued onto the next lines.
fn indent_continuations(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 8);
    for (i, l) in text.split('\n').enumerate() {
        if i > 0 {
            out.push('\n');
            if !l.starts_with([' ', '\t']) {
                out.push(' ');
            }
        }
        out.push_str(l);
    }
    out
}
