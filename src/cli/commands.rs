//! The subcommands: each takes parsed arguments, runs the pipeline and
//! prints results to standard output and diagnostics to standard error.

use std::borrow::Cow;
use std::io::{self, BufWriter, Write};

use miette::Diagnostic;

use super::args::{CheckArgs, Command, Common, DeriveArgs};
use super::{EX_DATAERR, EX_IOERR, EX_NOINPUT, EX_OK};
use crate::derive::{self, DeriveOptions, NumberFormat, NumberStyle};
use crate::load::{Input, Options};
use crate::pipeline::{self, Compilation};
use crate::progress::Progress;
use crate::simulation::Simulation;

/// Runs `cmd`. `color` is for diagnostics on standard error; the REPL
/// decides for standard output itself unless `repl_color` says.
pub fn run(cmd: &Command, color: bool, repl_color: Option<bool>) -> i32 {
    match cmd {
        Command::Check(c) => check(c, color),
        Command::Derive(d) => derive_cmd(d, color),
        Command::Disasm(c) => match compile(c, color) {
            Ok(comp) => emit_stdout(|out| {
                out.write_all(crate::bytecode::disasm(&comp.program, &comp.compiled).as_bytes())
            }),
            Err(code) => code,
        },
        Command::Build(b) => super::model::build_cmd(b, color),
        Command::Render(r) => super::model::render_cmd(r, color),
        Command::Pailou(p) => super::model::pailou_cmd(p, color),
        Command::Commands => {
            emit_stdout(|out| out.write_all(crate::lang::commands::help_text().as_bytes()))
        }
        Command::Watch(b) => super::watch::watch_cmd(b, color),
        Command::Lsp(l) => crate::lsp::run_stdio(l.source.options(&l.define)),
        #[cfg(feature = "studio")]
        Command::Studio(s) => super::studio::studio_cmd(s),
        Command::Repl(r) => crate::repl::run(crate::repl::Config {
            file: r.file.clone(),
            defines: r.define.clone(),
            step: r.step,
            derive: DeriveOptions {
                seed: r.seed,
                max_modules: r.max_modules,
                max_params: r.max_params,
            },
            echo: r.echo,
            color: repl_color,
        }),
    }
}

pub(super) fn report(d: &dyn Diagnostic, color: bool) {
    eprint!("{}", crate::diag::render(d, color));
}

/// Compiles, printing warnings; on failure prints every diagnostic and
/// returns the exit code.
pub(super) fn compile(c: &Common, color: bool) -> Result<Compilation, i32> {
    let opts = c.source.options(&c.define);
    compile_input(&Input::from_arg(&c.file), &c.file, &opts, color)
}

/// Compiles `input` (named `name` in the summary line) with `opts`.
pub(super) fn compile_input(
    input: &Input,
    name: &str,
    opts: &Options,
    color: bool,
) -> Result<Compilation, i32> {
    compile_reporting(input, name, opts, color).map_err(|(code, _)| code)
}

/// [`compile_input`], also naming on failure the files the grammar read.
pub(super) fn compile_reporting(
    input: &Input,
    name: &str,
    opts: &Options,
    color: bool,
) -> Result<Compilation, (i32, Vec<std::path::PathBuf>)> {
    match pipeline::compile(input, opts) {
        Ok(comp) => {
            for w in &comp.warnings {
                report(w.as_ref(), color);
            }
            Ok(comp)
        }
        Err(d) if d.is_input_error() => {
            eprint!("{}", d.render(color));
            Err((EX_NOINPUT, Vec::new()))
        }
        Err(diagnostics) => {
            let errors = diagnostics.error_count();
            eprint!("{}", diagnostics.render(color));
            eprintln!(
                "{}: {errors} error{}",
                name,
                if errors == 1 { "" } else { "s" }
            );
            Err((EX_DATAERR, diagnostics.files().to_vec()))
        }
    }
}

fn check(args: &CheckArgs, color: bool) -> i32 {
    let c = &args.common;
    match compile(c, color) {
        Ok(comp) => {
            let p = &comp.program;
            // The components the grammar places, found as `build` would
            // find them (nothing is read or built).
            let search = crate::mesh::ComponentSearch {
                grammar_dir: crate::driver::grammar_dir(&Input::from_arg(&c.file)),
                dirs: args.components.clone(),
                ..Default::default()
            };
            let missing = search.find_all(p);
            for e in &missing {
                report(e, color);
            }
            let n = missing.iter().filter(|e| crate::diag::is_error(*e)).count();
            if n > 0 {
                eprintln!("{}: {n} error{}", c.file, if n == 1 { "" } else { "s" });
                return EX_DATAERR;
            }
            let n = p.productions.len() + p.decomposition.len() + p.homomorphism.len();
            let w = comp.warnings.len();
            eprintln!(
                "{}: ok ({n} production{}, {} symbols{})",
                c.file,
                if n == 1 { "" } else { "s" },
                p.symbols.len(),
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
    let comp = match compile(&d.common, color) {
        Ok(c) => c,
        Err(code) => return code,
    };
    let (program, compiled) = (&comp.program, &comp.compiled);
    let opts = DeriveOptions {
        seed: d.run.seed,
        max_modules: d.run.max_modules,
        max_params: d.run.max_params,
    };
    let steps = d.run.steps.unwrap_or(program.derivation_length);
    if d.count {
        return count_cmd(d, &comp, opts, steps, color);
    }
    let style = match (d.precision, d.cpfg_format) {
        (_, true) => NumberStyle::PrintfG,
        (Some(n), false) => NumberStyle::Decimals(n),
        (None, false) => NumberStyle::Shortest,
    };
    let fmt = NumberFormat::for_program(program).with_style(style);
    let write = |out: &mut dyn Write| -> Result<(), Outcome> {
        let line = |sim: &mut Simulation, mut out: &mut dyn Write| -> Result<(), Outcome> {
            let shown = if d.homomorphism {
                // cpfg model files: the drawn string continues the
                // derivation's generator, as each of cpfg's interpretations
                // does (see `Simulation::drawn`).
                let h = sim.drawn().map_err(Outcome::Derive)?;
                for w in &h.warnings {
                    report(w, color);
                }
                Cow::Owned(h.modules)
            } else {
                Cow::Borrowed(sim.current())
            };
            shown
                .write_string_with(&program.symbols, fmt, &mut out)
                .map_err(Outcome::Io)?;
            out.write_all(b"\n").map_err(Outcome::Io)
        };
        let mut deriv =
            Simulation::new(program, compiled, opts.clone(), steps).map_err(Outcome::Derive)?;
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
        for w in deriv.derivation().warnings() {
            report(w, color);
        }
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
        Some(path) => crate::export::atomic::write_file(path, |f| write(f)),
    };
    match result {
        Ok(()) => EX_OK,
        Err(Outcome::Derive(e)) => {
            report(&e, color);
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
fn count_cmd(
    d: &DeriveArgs,
    comp: &Compilation,
    opts: DeriveOptions,
    steps: u32,
    color: bool,
) -> i32 {
    let program = &comp.program;
    let counts = match derive::count(program, &comp.compiled, opts, steps) {
        Ok(c) => c,
        Err(e) => {
            report(&e, color);
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
    let mut text = format!("{} modules\n", show(counts.total()));
    for (s, &n) in counts.per_symbol.iter().enumerate() {
        if n > 0 {
            let name = program.symbols.name(s as u32);
            text.push_str(&format!("{name} {}\n", show(n)));
        }
    }
    match &d.output {
        None => emit_stdout(|out| out.write_all(text.as_bytes())),
        Some(path) => {
            match crate::export::atomic::write_file(path, |f| f.write_all(text.as_bytes())) {
                Ok(()) => EX_OK,
                Err(e) => {
                    eprintln!("lsys: cannot write the output: {e}");
                    EX_IOERR
                }
            }
        }
    }
}

enum Outcome {
    Derive(derive::DeriveError),
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
