//! The subcommands: each takes parsed arguments, runs the pipeline and
//! prints results to standard output and diagnostics to standard error.

use std::io::{self, BufWriter, Write};

use super::args::{CheckArgs, Command, Common, DeriveArgs};
use super::{EX_DATAERR, EX_IOERR, EX_NOINPUT, EX_OK};
use crate::driver;
use crate::progress::Progress;
use crate::{Diagnostics, Grammar, GrammarOptions, Numbers};

/// Runs `cmd`. `color` is for diagnostics on standard error; the REPL
/// decides for standard output itself unless `repl_color` says.
pub fn run(cmd: &Command, color: bool, repl_color: Option<bool>) -> i32 {
    match cmd {
        Command::Check(c) => check(c, color),
        Command::Derive(d) => derive_cmd(d, color),
        Command::Disasm(c) => match compile(c, GrammarOptions::default(), color) {
            Ok(g) => emit_stdout(|out| out.write_all(g.disasm().as_bytes())),
            Err(code) => code,
        },
        Command::Build(b) => super::model::build_cmd(b, color),
        Command::Render(r) => super::model::render_cmd(r, color),
        Command::Pailou(p) => super::model::pailou_cmd(p, color),
        Command::Infer(i) => super::infer::infer_cmd(i, color),
        Command::Commands => emit_stdout(|out| out.write_all(driver::turtle_commands().as_bytes())),
        Command::Watch(b) => super::watch::watch_cmd(b, color),
        Command::Batch(b) => super::batch::batch_cmd(b, color),
        // The language server keeps its own access to the parser and the
        // resolver: it must work on broken text (src/lsp/mod.rs).
        Command::Lsp(l) => crate::lsp::run_stdio(
            l.source
                .apply(GrammarOptions::default().defines_from(&l.define)),
        ),
        #[cfg(feature = "studio")]
        Command::Studio(s) => super::studio::studio_cmd(s),
        Command::Repl(r) => crate::repl::run(crate::repl::Config {
            file: r.file.clone(),
            step: r.step,
            options: GrammarOptions::default()
                .defines_from(&r.define)
                .max_modules(r.max_modules)
                .max_params(r.max_params)
                .seed_option(r.seed),
            echo: r.echo,
            color: repl_color,
        }),
    }
}

/// Compiles the FILE of `c` with its flags on top of `more`, printing
/// warnings; on failure prints every diagnostic and returns the exit code.
fn compile(c: &Common, more: GrammarOptions, color: bool) -> Result<Grammar, i32> {
    match c
        .source
        .apply(more.defines_from(&c.define))
        .from_path(&c.file)
    {
        Ok(g) => {
            eprint!("{}", g.warnings().render(color));
            Ok(g)
        }
        Err(d) if d.is_input_error() => {
            eprint!("{}", d.render(color));
            Err(EX_NOINPUT)
        }
        Err(d) => {
            let errors = d.error_count();
            eprint!("{}", d.render(color));
            eprintln!(
                "{}: {errors} error{}",
                c.file,
                if errors == 1 { "" } else { "s" }
            );
            Err(EX_DATAERR)
        }
    }
}

fn check(args: &CheckArgs, color: bool) -> i32 {
    let c = &args.common;
    let more = args
        .components
        .iter()
        .fold(GrammarOptions::default(), |o, d| o.components_dir(d));
    match compile(c, more, color) {
        Ok(g) => {
            // The components the grammar places, found as `build` would
            // find them (nothing is read or built).
            let missing = g.missing_components();
            eprint!("{}", missing.render(color));
            let n = missing.error_count();
            if n > 0 {
                eprintln!("{}: {n} error{}", c.file, if n == 1 { "" } else { "s" });
                return EX_DATAERR;
            }
            let n = g.rule_count();
            let w = g.warnings().len();
            eprintln!(
                "{}: ok ({n} production{}, {} symbols{})",
                c.file,
                if n == 1 { "" } else { "s" },
                g.symbol_count(),
                if w > 0 {
                    format!(", {w} warning{}", if w == 1 { "" } else { "s" })
                } else {
                    String::new()
                }
            );
            EX_OK
        }
        Err(code) => code,
    }
}

fn derive_cmd(d: &DeriveArgs, color: bool) -> i32 {
    let more = GrammarOptions::default()
        .max_modules(d.run.max_modules)
        .max_params(d.run.max_params)
        .seed_option(d.run.seed);
    let g = match compile(&d.common, more, color) {
        Ok(g) => g,
        Err(code) => return code,
    };
    if let Some(path) = &d.output {
        if let Err(e) = driver::refuse_inputs(path, &g) {
            eprint!("{}", driver::render_diagnostic(&e, color));
            return EX_DATAERR;
        }
    }
    let steps = d.run.steps.unwrap_or(g.derivation_length());
    if d.run.steps.is_none() {
        if let Some(note) = g.zero_steps_note() {
            eprintln!("{note}");
        }
    }
    if d.count {
        return count_cmd(d, &g, steps, color);
    }
    let numbers = match (d.precision, d.cpfg_format) {
        (_, true) => Numbers::Cpfg,
        (Some(n), false) => Numbers::Decimals(n),
        (None, false) => Numbers::Shortest,
    };
    let write = |out: &mut dyn Write| -> Result<(), Outcome> {
        let line = |deriv: &mut crate::Derivation, out: &mut dyn Write| -> Result<(), Outcome> {
            if d.homomorphism {
                let drawn = deriv.drawn().map_err(Outcome::Derive)?;
                eprint!("{}", drawn.warnings.render(color));
                drawn.write(numbers, out)?;
            } else {
                deriv.write_current(numbers, out)?;
            }
            out.write_all(b"\n").map_err(Outcome::Io)
        };
        let mut deriv = g.derivation(steps).map_err(Outcome::Derive)?;
        if d.every {
            line(&mut deriv, out)?;
        }
        let progress = Progress::new(true);
        if d.every {
            for done in 0..steps {
                progress.step(done, steps);
                deriv.step().map_err(Outcome::Derive)?;
                line(&mut deriv, out)?;
            }
        } else {
            // Only the last string is printed: the steps may be expanded
            // depth first without building the ones in between.
            deriv
                .run(&mut |done, of| progress.step(done, of))
                .map_err(Outcome::Derive)?;
        }
        deriv.finish().map_err(Outcome::Derive)?;
        drop(progress);
        eprint!("{}", deriv.warnings().render(color));
        if !d.every {
            line(&mut deriv, out)?;
        }
        Ok(())
    };
    let result = match &d.output {
        None => {
            let stdout = io::stdout();
            let mut out = BufWriter::with_capacity(1 << 16, stdout.lock());
            write(&mut out).and_then(|_| out.flush().map_err(Outcome::Io))
        }
        Some(path) => driver::write_file(path, |f| write(f)),
    };
    match result {
        Ok(()) => EX_OK,
        Err(Outcome::Derive(e)) => {
            eprint!("{}", e.render(color));
            EX_DATAERR
        }
        Err(Outcome::Io(e)) if e.kind() == io::ErrorKind::BrokenPipe => EX_OK,
        Err(Outcome::Io(e)) => {
            eprintln!("lsys: cannot write the output: {e}");
            EX_IOERR
        }
    }
}

/// `lsys derive --count`: `N modules` on the first line, then `SYMBOL N`
/// for every symbol present, in symbol order.
fn count_cmd(d: &DeriveArgs, g: &Grammar, steps: u32, color: bool) -> i32 {
    let counts = match g.count(steps) {
        Ok(c) => c,
        Err(e) => {
            eprint!("{}", e.render(color));
            return EX_DATAERR;
        }
    };
    // Counts saturate at u64::MAX: say so rather than print a wrong number.
    let show = |n: u64| {
        if n == u64::MAX {
            format!("at least {n}")
        } else {
            n.to_string()
        }
    };
    let total = counts.iter().fold(0u64, |a, (_, n)| a.saturating_add(*n));
    let mut text = format!("{} modules\n", show(total));
    for (name, n) in &counts {
        text.push_str(&format!("{name} {}\n", show(*n)));
    }
    match &d.output {
        None => emit_stdout(|out| out.write_all(text.as_bytes())),
        Some(path) => match driver::write_file(path, |f| f.write_all(text.as_bytes())) {
            Ok(()) => EX_OK,
            Err(e) => {
                eprintln!("lsys: cannot write the output: {e}");
                EX_IOERR
            }
        },
    }
}

enum Outcome {
    Derive(Diagnostics),
    Io(io::Error),
}

impl From<io::Error> for Outcome {
    fn from(e: io::Error) -> Self {
        Outcome::Io(e)
    }
}

fn emit_stdout(body: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> i32 {
    let stdout = io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    match body(&mut out).and_then(|_| out.flush()) {
        Ok(()) => EX_OK,
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => EX_OK,
        Err(e) => {
            eprintln!("lsys: cannot write the output: {e}");
            EX_IOERR
        }
    }
}
