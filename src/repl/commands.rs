//! The REPL's commands, in one table ([`COMMANDS`]: name, arguments, help,
//! what the argument completes to, and the function that runs it) that
//! drives dispatch, `:help` and tab completion. Input: a command name (or
//! a unique prefix of one) and its argument text; output: the command's
//! text or error.

use std::fmt::Write;

use crate::driver::session::{Out, Session};

/// What tab completion offers for a command's argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arg {
    None,
    /// A path.
    File,
    /// A define name (`:set`).
    Define,
    /// A command name (`:help`).
    Command,
    /// A turtle view (`:render`'s second word).
    View,
}

/// One REPL command.
pub struct Command {
    pub name: &'static str,
    /// The arguments as `:help` shows them.
    pub args: &'static str,
    pub help: &'static str,
    pub arg: Arg,
    pub run: fn(&mut Session, &str) -> Out,
}

/// Every command, in the order `:help` lists them.
pub const COMMANDS: &[Command] = &[
    Command {
        name: "load",
        args: "FILE",
        help: "load a grammar (a file or std:NAME) and go to step 0; on errors the previous grammar stays",
        arg: Arg::File,
        run: |s, a| s.load(a),
    },
    Command {
        name: "reload",
        args: "",
        help: "read the file again (edits typed here are dropped), keep the step and the defines set",
        arg: Arg::None,
        run: |s, _| s.reload(),
    },
    Command {
        name: "save",
        args: "[FILE]",
        help: "write the grammar with the edits typed here and the defines set into FILE (default: the file loaded), then go on from it",
        arg: Arg::File,
        run: |s, a| s.save(a),
    },
    Command {
        name: "step",
        args: "[N]",
        help: "derive N more steps (default 1)",
        arg: Arg::None,
        run: |s, a| {
            let n = count(a, "step")?;
            let target = s.step().saturating_add(n);
            s.goto(target)
        },
    },
    Command {
        name: "back",
        args: "[N]",
        help: "go back N steps (default 1)",
        arg: Arg::None,
        run: |s, a| {
            let n = count(a, "back")?;
            let target = s.step().saturating_sub(n);
            s.goto(target)
        },
    },
    Command {
        name: "goto",
        args: "N",
        help: "go to step N",
        arg: Arg::None,
        run: |s, a| {
            let n: u32 = a
                .parse()
                .map_err(|_| format!("`:goto` needs a step number, not `{a}`"))?;
            s.goto(n)
        },
    },
    Command {
        name: "reset",
        args: "",
        help: "go back to step 0, the axiom",
        arg: Arg::None,
        run: |s, _| s.goto(0),
    },
    Command {
        name: "show",
        args: "[RANGE]",
        help: "the current string: abbreviated, or modules A..B (from 0, B excluded), A.., ..B, A, or all",
        arg: Arg::None,
        run: |s, a| s.show(a),
    },
    Command {
        name: "count",
        args: "",
        help: "modules per symbol in the current string",
        arg: Arg::None,
        run: |s, _| s.count(),
    },
    Command {
        name: "diff",
        args: "",
        help: "what the last step changed: counts per symbol and, for short strings, where",
        arg: Arg::None,
        run: |s, _| s.diff(),
    },
    Command {
        name: "rules",
        args: "",
        help: "the productions, numbered (`*` marks those typed in this session)",
        arg: Arg::None,
        run: |s, _| s.rules(),
    },
    Command {
        name: "drop",
        args: "N",
        help: "remove rule N",
        arg: Arg::None,
        run: |s, a| {
            let n: usize = a
                .parse()
                .map_err(|_| format!("`:drop` needs a rule number, not `{a}`"))?;
            s.drop_rule(n)
        },
    },
    Command {
        name: "axiom",
        args: "[MODULES]",
        help: "show the axiom, or replace it and derive again to the same step",
        arg: Arg::None,
        run: |s, a| s.set_axiom(a),
    },
    Command {
        name: "set",
        args: "NAME=VALUE",
        help: "override a #define and derive again to the same step (`:set NAME` restores the file's value)",
        arg: Arg::Define,
        run: |s, a| s.set_define(a),
    },
    Command {
        name: "defines",
        args: "",
        help: "the #defines and their values",
        arg: Arg::None,
        run: |s, _| s.defines(),
    },
    Command {
        name: "seed",
        args: "[N]",
        help: "show the seed, or set it and derive again to the same step",
        arg: Arg::None,
        run: |s, a| s.set_seed(a),
    },
    Command {
        name: "precision",
        args: "[N|off]",
        help: "print parameters rounded to N decimal places (as `lsys derive --precision N`), or in the shortest form (`off`, the default)",
        arg: Arg::None,
        run: |s, a| s.precision(a),
    },
    Command {
        name: "undo",
        args: "",
        help: "take back the last edit (a typed production, `:drop`, `:axiom`, `:set`, `:seed`), again for the one before",
        arg: Arg::None,
        run: |s, _| s.undo(),
    },
    Command {
        name: "disasm",
        args: "[RULE]",
        help: "the bytecode of every production, or of rule RULE",
        arg: Arg::None,
        run: |s, a| s.disasm(a),
    },
    Command {
        name: "export",
        args: "FILE",
        help: "build the current string into FILE.glb, .gltf, .obj or .png (as `lsys build`)",
        arg: Arg::File,
        run: |s, a| s.export(a, false),
    },
    Command {
        name: "render",
        args: "FILE.png [VIEW]",
        help: "render the current string to a PNG picture; VIEW is iso (default), front, side or top",
        arg: Arg::File,
        run: |s, a| s.export(a, true),
    },
    Command {
        name: "stats",
        args: "",
        help: "the string, the history kept, and the model the current string builds",
        arg: Arg::None,
        run: |s, _| s.stats(),
    },
    Command {
        name: "help",
        args: "[COMMAND]",
        help: "this list, or one command's help",
        arg: Arg::Command,
        run: |_, a| help(a),
    },
    Command {
        name: "quit",
        args: "",
        help: "leave (Ctrl-D, `quit` or `exit` too)",
        arg: Arg::None,
        run: |s, _| {
            s.request_quit();
            Ok(String::new())
        },
    },
];

/// The command `name` names: exactly, or as the only command it begins.
pub fn find(name: &str) -> Result<&'static Command, String> {
    if let Some(c) = COMMANDS.iter().find(|c| c.name == name) {
        return Ok(c);
    }
    let matches: Vec<&Command> = COMMANDS
        .iter()
        .filter(|c| !name.is_empty() && c.name.starts_with(name))
        .collect();
    match matches.as_slice() {
        [c] => Ok(c),
        [] => Err(format!(
            "unknown command `:{name}`; `:help` lists the commands"
        )),
        many => Err(format!(
            "`:{name}` could be {}",
            many.iter()
                .map(|c| format!(":{}", c.name))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// `:help [COMMAND]`.
pub fn help(about: &str) -> Out {
    let about = about.trim().trim_start_matches(':');
    if !about.is_empty() {
        let c = find(about)?;
        return Ok(format!("{}\n  {}", usage(c), c.help));
    }
    let w = COMMANDS.iter().map(|c| usage(c).len()).max().unwrap_or(0);
    let mut out = String::from("commands:\n");
    for c in COMMANDS {
        let _ = writeln!(out, "  {:<w$}  {}", usage(c), c.help);
    }
    out.push_str(
        "anything else:\n\
         \x20 A(x) --> B(x+1)    a production: added, or replacing the one with the same predecessor and condition\n\
         \x20 \x20   F [+A]          a line starting with blanks continues the production above\n\
         \x20 Axiom: F X         replaces the axiom\n\
         \x20 A(3) B             modules: rewritten once with the current rules, the result printed\n\
         Ctrl-C stops a derivation between steps; Tab completes commands, module and define names.",
    );
    Ok(out)
}

fn usage(c: &Command) -> String {
    if c.args.is_empty() {
        format!(":{}", c.name)
    } else {
        format!(":{} {}", c.name, c.args)
    }
}

/// `[N]` of `:step` and `:back`: 1 when absent.
fn count(arg: &str, cmd: &str) -> Result<u32, String> {
    if arg.is_empty() {
        return Ok(1);
    }
    arg.parse()
        .map_err(|_| format!("`:{cmd}` takes a number of steps, not `{arg}`"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_prefixes_resolve() {
        for (i, a) in COMMANDS.iter().enumerate() {
            for b in &COMMANDS[i + 1..] {
                assert_ne!(a.name, b.name);
            }
        }
        assert_eq!(find("q").unwrap().name, "quit");
        assert_eq!(find("def").unwrap().name, "defines");
        assert!(find("s").err().unwrap().contains(":step"));
        assert!(find("zz").is_err());
    }

    #[test]
    fn help_lists_every_command() {
        let h = help("").unwrap();
        for c in COMMANDS {
            assert!(h.contains(&format!(":{}", c.name)), "{}", c.name);
        }
        assert!(help("goto").unwrap().starts_with(":goto N"));
    }
}
