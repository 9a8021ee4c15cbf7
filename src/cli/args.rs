//! Command-line arguments (clap).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

#[derive(Parser, Debug)]
#[command(
    name = "lsys",
    version,
    about = "Compile and derive parametric L-systems (cpfg notation and the Pailou paper's)",
    after_help = "FILE is a path to an .lsys (or cpfg .l) file, or std:NAME for a standard library grammar (e.g. std:toukung_middle)."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
    /// Colour in diagnostics.
    #[arg(long, global = true, value_enum, default_value_t = Color::Auto)]
    pub color: Color,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Color {
    Auto,
    Always,
    Never,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Check a grammar and report every error and warning (exit 0 when clean).
    Check(Common),
    /// Derive a grammar and print the module string.
    Derive(DeriveArgs),
    /// Print the bytecode the grammar compiles to.
    Disasm(Common),
}

#[derive(Args, Debug)]
pub struct Common {
    /// The grammar: a file, or std:NAME.
    pub file: String,
    /// Override a #define for this run: -D NAME=VALUE (repeatable).
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
}

#[derive(Args, Debug)]
pub struct DeriveArgs {
    #[command(flatten)]
    pub common: Common,
    /// Derivation steps (default: the file's `derivation length:`).
    #[arg(short = 'n', long = "steps", value_name = "STEPS")]
    pub steps: Option<u32>,
    /// Seed of the random generator, 0 to 4294967295 (overrides the file's `seed:`).
    #[arg(long, value_parser = clap::value_parser!(u64).range(..=u32::MAX as u64))]
    pub seed: Option<u64>,
    /// Print the string after every step, one line per step, from the axiom.
    #[arg(long)]
    pub every: bool,
    /// Print the string after the homomorphism (what the turtle draws).
    #[arg(long)]
    pub homomorphism: bool,
    /// Stop with an error when a string would exceed this many modules.
    #[arg(long, value_name = "N", default_value_t = 50_000_000)]
    pub max_modules: usize,
    /// Stop with an error when a string would hold more parameter values than this.
    #[arg(long, value_name = "N", default_value_t = 200_000_000)]
    pub max_params: usize,
    /// Write the string here instead of standard output.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: Option<PathBuf>,
}

fn parse_define(s: &str) -> Result<(String, String), String> {
    match s.split_once('=') {
        Some((n, v)) if !n.trim().is_empty() && !v.trim().is_empty() => {
            Ok((n.trim().to_string(), v.trim().to_string()))
        }
        _ => Err(format!("`{s}` is not NAME=VALUE (e.g. -D NTL=7)")),
    }
}
