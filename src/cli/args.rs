//! Command-line arguments (clap).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::driver::limits::*;
use crate::driver::{Correction, Style, View};

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
    Check(CheckArgs),
    /// Derive a grammar and print the module string.
    Derive(DeriveArgs),
    /// Print the bytecode the grammar compiles to.
    Disasm(Common),
    /// Build a model: derive, run the turtle, write .glb, .gltf, .obj or .png.
    Build(BuildArgs),
    /// Render a picture of the model to PNG (a software renderer; no GPU needed).
    Render(RenderArgs),
    /// List the turtle commands: symbol, parameters, default, meaning.
    Commands,
    /// Build a Pailou from a component graph or a style: lsys pailou --style 4-3-7 --type ridge -o p.glb
    Pailou(PailouArgs),
    /// Infer a hall's shape grammar (or a Pailou's style and proportions) from an elevation line drawing (PNG or SVG): lsys infer front.png -o hall.lsys
    Infer(InferArgs),
    /// Explore a grammar step by step: step, go back, show, edit rules, set defines, export.
    Repl(ReplArgs),
    /// Build many models from a manifest (one JSON item a line) into a folder with an index; resumable, in shards (see docs/batch.md).
    Batch(BatchArgs),
    /// Rebuild the output whenever the grammar or a file it includes changes (Ctrl-C stops).
    Watch(BuildArgs),
    /// Run the language server on standard input and output (for editors; see docs/editors.md).
    Lsp(LspArgs),
    /// The Pailou editor and live grammar preview in the browser, on 127.0.0.1 (see docs/studio.md).
    #[cfg(feature = "studio")]
    Studio(super::studio::StudioArgs),
}

/// `lsys batch`: a manifest of items, each built as `lsys build` would.
#[derive(Args, Debug)]
pub struct BatchArgs {
    /// The manifest: one JSON object a line, {"id", "grammar", "defines", "seed", "steps", "format"}; relative grammar paths start from its folder.
    pub manifest: PathBuf,
    /// The folder the models (ID.FORMAT) and index.jsonl go into; created if missing. Items its index records are not built again.
    #[arg(long = "out", value_name = "DIR")]
    pub out: PathBuf,
    /// Build only the items whose position in the manifest (from 0) modulo N is I, e.g. --shard $SLURM_ARRAY_TASK_ID/8. Shards may share one DIR.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    pub shard: Option<(usize, usize)>,
    /// Items built at once, each on its own thread.
    #[arg(short = 'j', long, value_name = "K", default_value_t = 1,
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..))]
    pub jobs: usize,
}

/// `--shard I/N`: the batch's own parser, its message as clap's.
fn parse_shard(s: &str) -> Result<(usize, usize), String> {
    crate::driver::batch::parse_shard(s).map_err(|e| {
        use miette::Diagnostic;
        match e.help() {
            Some(h) => format!("{e}; {h}"),
            None => e.to_string(),
        }
    })
}

#[derive(Args, Debug)]
pub struct LspArgs {
    /// Override a #define in every grammar the server compiles: -D NAME=VALUE (repeatable).
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
    #[command(flatten)]
    pub source: SourceArgs,
}

#[derive(Args, Debug)]
pub struct CheckArgs {
    #[command(flatten)]
    pub common: Common,
    /// Also look for components (NAME.obj or NAME.lsys) in this directory (repeatable; after `components/` beside the grammar), as `build` would.
    #[arg(long = "components", value_name = "DIR")]
    pub components: Vec<PathBuf>,
}

#[derive(Args, Debug)]
pub struct ReplArgs {
    /// A grammar to load at the start: a file, or std:NAME.
    pub file: Option<String>,
    /// Override a #define: -D NAME=VALUE (repeatable; `:set` changes it in the session).
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
    /// Start at this derivation step.
    #[arg(short = 'n', long = "step", value_name = "N", default_value_t = 0)]
    pub step: u32,
    /// Seed of the random generator, 0 to 4294967295 (overrides the file's `seed:`).
    #[arg(long, value_parser = clap::value_parser!(u64).range(..=u32::MAX as u64))]
    pub seed: Option<u64>,
    /// Stop with an error when a string would exceed this many modules.
    #[arg(long, value_name = "N", default_value_t = 50_000_000)]
    pub max_modules: usize,
    /// Stop with an error when a string would hold more parameter values than this.
    #[arg(long, value_name = "N", default_value_t = 200_000_000)]
    pub max_params: usize,
    /// When commands come from a pipe or file, print each one as `> COMMAND` before its output.
    #[arg(long)]
    pub echo: bool,
}

#[derive(Args, Debug)]
pub struct Common {
    /// The grammar: a file, or std:NAME.
    pub file: String,
    /// Override a #define for this run: -D NAME=VALUE (repeatable).
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
    #[command(flatten)]
    pub source: SourceArgs,
}

/// Where includes may come from and how deep input may nest (see
/// docs/limits.md).
#[derive(Args, Debug, Clone)]
pub struct SourceArgs {
    /// Also allow and search this folder for `#include "..."` (repeatable; after the including file's folder).
    #[arg(long = "include-dir", value_name = "DIR")]
    pub include_dir: Vec<PathBuf>,
    /// Stop with an error when includes nest deeper than this many files.
    #[arg(long, value_name = "N", default_value_t = MAX_INCLUDE_DEPTH)]
    pub max_include_depth: usize,
    /// Stop with an error when `(` and `{` nest deeper than this (at most 4096).
    #[arg(long, value_name = "N", default_value_t = MAX_NESTING,
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=MAX_NESTING_CEILING as u64))]
    pub max_nesting: usize,
    /// Stop with an error when one expression has more operators than this (at most 100000).
    #[arg(long, value_name = "N", default_value_t = MAX_OPERATORS,
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=MAX_OPERATORS_CEILING as u64))]
    pub max_operators: usize,
    /// Read the file in this notation whatever its name (`.l`) and its
    /// `dialect:` header say.
    #[arg(long, value_enum, value_name = "DIALECT")]
    pub dialect: Option<DialectArg>,
    /// The environment that answers `?E` when the grammar names none, as
    /// the `environment:` header writes it: `collision(radius: 0.01)`,
    /// `light(transmittance: 0.3)`.
    #[arg(long, value_name = "SPEC")]
    pub environment: Option<String>,
}

/// `--dialect`.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum DialectArg {
    /// The Pailou paper's Table 1 (`%` rolls 180°, `$` pitches 180°).
    Paper,
    /// cpfg's (`%` cuts the branch, `$` ends a sub-L-system; f32 parameters).
    Cpfg,
}

/// How far and how to derive (shared by `derive`, `build` and `render`).
impl SourceArgs {
    /// These flags set on `o`.
    pub fn apply(&self, mut o: crate::GrammarOptions) -> crate::GrammarOptions {
        for dir in &self.include_dir {
            o = o.include_dir(dir);
        }
        o = o
            .max_include_depth(self.max_include_depth)
            .parser_limits(self.max_nesting, self.max_operators);
        if let Some(d) = self.dialect {
            o = o.dialect(match d {
                DialectArg::Paper => crate::Dialect::Paper,
                DialectArg::Cpfg => crate::Dialect::Cpfg,
            });
        }
        if let Some(spec) = &self.environment {
            o = o.environment(spec);
        }
        o
    }
}

impl LookArgs {
    /// These flags set on `o`.
    pub fn apply(&self, mut o: crate::GrammarOptions) -> crate::GrammarOptions {
        if let Some(a) = self.angle {
            o = o.angle(a);
        }
        if let Some(s) = self.step {
            o = o.step(s);
        }
        if let Some(w) = self.width {
            o = o.width(w);
        }
        for dir in &self.components {
            o = o.components_dir(dir);
        }
        if let Some(n) = self.facets {
            o = o.facets(n);
        }
        o.detail(self.detail)
            .instanced(self.instanced)
            .max_triangles(self.max_triangles)
    }
}

#[derive(Args, Debug)]
pub struct DeriveRun {
    /// Derivation steps (default: the file's `derivation length:`).
    #[arg(short = 'n', long = "steps", value_name = "STEPS")]
    pub steps: Option<u32>,
    /// Seed of the random generator, 0 to 4294967295 (overrides the file's `seed:`).
    #[arg(long, value_parser = clap::value_parser!(u64).range(..=u32::MAX as u64))]
    pub seed: Option<u64>,
    /// Stop with an error when a string would exceed this many modules.
    #[arg(long, value_name = "N", default_value_t = 50_000_000)]
    pub max_modules: usize,
    /// Stop with an error when a string would hold more parameter values than this.
    #[arg(long, value_name = "N", default_value_t = 200_000_000)]
    pub max_params: usize,
}

#[derive(Args, Debug)]
pub struct DeriveArgs {
    #[command(flatten)]
    pub common: Common,
    #[command(flatten)]
    pub run: DeriveRun,
    /// Print the string after every step, one line per step, from the axiom.
    #[arg(long)]
    pub every: bool,
    /// Print the string after the homomorphism (what the turtle draws).
    #[arg(long)]
    pub homomorphism: bool,
    /// Print the number of modules (in all, then per symbol) instead of the string. Grammars whose productions rewrite each module on its own (no context, no probabilities, no `ran`, no decomposition) are counted without building the string, however long it is.
    #[arg(long, conflicts_with_all = ["every", "homomorphism"])]
    pub count: bool,
    /// Round parameters to N decimal places, trailing zeros removed (for stable snapshots); never more digits than the default form.
    #[arg(long, value_name = "N", conflicts_with = "count")]
    pub precision: Option<u8>,
    /// Print parameters as cpfg's -str output does: C's printf("%g"), six significant digits (1e+06, 1.5e-05, 123457).
    #[arg(long, conflicts_with_all = ["count", "precision"])]
    pub cpfg_format: bool,
    /// Write the string here instead of standard output.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: Option<PathBuf>,
}

/// What turns a derived string into a model (shared by `build` and `render`).
#[derive(Args, Debug)]
pub struct ModelArgs {
    #[command(flatten)]
    pub common: Common,
    #[command(flatten)]
    pub run: DeriveRun,
    #[command(flatten)]
    pub look: LookArgs,
}

/// Turtle defaults, components and meshing (shared by `build`, `render`
/// and `pailou`).
#[derive(Args, Debug)]
pub struct LookArgs {
    /// Default turning angle in degrees (overrides the file's `angle:`; default 90).
    #[arg(long, value_name = "DEGREES", allow_negative_numbers = true, value_parser = finite)]
    pub angle: Option<f64>,
    /// Default step length (overrides the file's `step:`; default 1).
    #[arg(long, value_name = "D", value_parser = finite)]
    pub step: Option<f64>,
    /// Initial line width, the tube diameter (overrides the file's `width:`; default 0.1).
    #[arg(long, value_name = "W", value_parser = finite)]
    pub width: Option<f64>,
    /// Also look for components (NAME.obj or NAME.lsys) in this directory (repeatable; after `components/` beside the grammar).
    #[arg(long = "components", value_name = "DIR")]
    pub components: Vec<PathBuf>,
    /// Level of detail: 0 a light preview (bare roofs, built-in components with a third of the segments on their curves, fewer facets on thin tubes), 1 roofs with rows of round tiles, 2 twice the tiles and rounder thin tubes.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u8).range(0..=2))]
    pub detail: u8,
    /// Facets around tubes, spheres and discs (3 to 64). Without it spheres and discs get 8, and each tube up to 8: fewer when it is thin against the whole model (see --detail).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(3..=64))]
    pub facets: Option<u32>,
    /// Draw tubes as one cylinder per straight segment, all placements of one mesh: a .glb/.gltf then uses EXT_mesh_gpu_instancing (about 40 bytes a segment; viewers without the extension refuse the file). Joints show where branches bend: for line-like models.
    #[arg(long)]
    pub instanced: bool,
    /// Stop with an error when the model would have more triangles than this.
    #[arg(long, value_name = "N", default_value_t = 100_000_000)]
    pub max_triangles: usize,
    /// Print statistics as JSON to standard output (modules, instances, vertices, triangles, bounds, timings).
    #[arg(long)]
    pub stats: bool,
    /// Check the structure: every Pailou part touches its support, and no two components interpenetrate unless the relation matrix joins them (always on for `lsys pailou`; see docs/pailou.md).
    #[arg(long)]
    pub collisions: bool,
    /// With a guided scene (FILE.toml, docs/guided.md): draw its guides and links too.
    #[arg(long)]
    pub guides: bool,
}

/// `lsys infer`: a grammar from an elevation drawing.
#[derive(Args, Debug)]
pub struct InferArgs {
    /// The drawing: a PNG or SVG of dark lines on a light background.
    pub drawing: PathBuf,
    /// The grammar to write (.lsys).
    #[arg(short = 'o', long = "output", value_name = "OUT.lsys")]
    pub output: PathBuf,
    /// Also write the labelled shape tree as JSON.
    #[arg(long, value_name = "OUT.json")]
    pub tree: Option<PathBuf>,
    /// Separator strokes: a PNG or SVG of the drawing's size whose lines
    /// are added to the drawing where it is ambiguous (a missing line,
    /// two parts drawn as one).
    #[arg(long, value_name = "LINES")]
    pub strokes: Option<PathBuf>,
    /// Bridge breaks in the lines up to twice this many pixels.
    #[arg(long, value_name = "PIXELS", default_value_t = 2,
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(0..=8))]
    pub gap: usize,
    /// Metres per pixel of the drawing (default: the columns are 4.2 m high).
    #[arg(long, value_name = "METRES", value_parser = positive)]
    pub scale: Option<f64>,
    /// Correct a label: the node whose box (as `--tree` gives it) is
    /// X0,Y0,X1,Y1 is a LABEL (door, window, wall, bracket, ...); its parts
    /// with its old label follow. Repeatable.
    #[arg(long = "label", value_name = "X0,Y0,X1,Y1=LABEL", value_parser = correction)]
    pub labels: Vec<Correction>,
}

/// `X0,Y0,X1,Y1=LABEL` for `--label`.
fn correction(s: &str) -> Result<Correction, String> {
    let (b, label) = s
        .split_once('=')
        .ok_or("write the node's box and its label: X0,Y0,X1,Y1=door")?;
    let nums: Vec<i32> = b
        .split(',')
        .map(|n| n.trim().parse::<i32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("`{b}`: the box is four whole numbers of pixels, X0,Y0,X1,Y1"))?;
    let bbox: [i32; 4] = nums
        .try_into()
        .map_err(|_| format!("`{b}`: the box is four whole numbers of pixels, X0,Y0,X1,Y1"))?;
    let label = crate::driver::infer_label(label.trim()).map_err(|e| {
        use miette::Diagnostic;
        format!(
            "{e}; {}",
            e.help().map(|h| h.to_string()).unwrap_or_default()
        )
    })?;
    Ok(Correction {
        bbox,
        label: label.to_string(),
    })
}

/// A finite number above zero.
fn positive(s: &str) -> Result<f64, String> {
    match finite(s)? {
        x if x > 0.0 => Ok(x),
        _ => Err("must be above zero".to_string()),
    }
}

/// `lsys pailou`: a Pailou from a component graph or a style.
#[derive(Args, Debug)]
pub struct PailouArgs {
    /// A component graph (.toml, see docs/pailou.md); without it, --style.
    pub graph: Option<PathBuf>,
    /// The style NP-NE-NR: pillars and entrances on the ground, roofs in all (see docs/pailou.md).
    #[arg(long, default_value = "4-3-7", conflicts_with = "graph")]
    pub style: String,
    /// The relation matrix that attachments are checked against (default: the library's).
    #[arg(long, value_name = "FILE")]
    pub relations: Option<PathBuf>,
    /// Print the component graph (TOML) of the style, to edit and build with `lsys pailou GRAPH`.
    #[arg(long)]
    pub emit_graph: bool,
    /// Ridge type (eaves roofs on Toukungs) or pillar type (clipped roofs, pillars rising above them); a graph says its own.
    #[arg(long = "type", value_enum, default_value_t = PailouTypeArg::Ridge, conflicts_with = "graph")]
    pub kind: PailouTypeArg,
    /// Override a #define of the Pailou grammar: -D NAME=VALUE, -D 'dec[1,1,3]=0' (repeatable).
    #[arg(short = 'D', value_name = "NAME=VALUE", value_parser = parse_define)]
    pub define: Vec<(String, String)>,
    /// Print the layout chart (entrances per level).
    #[arg(long)]
    pub chart: bool,
    /// Print the generated grammar (the library's Pailou with this style's tables), to continue by hand.
    #[arg(long)]
    pub emit_lsys: bool,
    /// The model or picture to write: .glb, .gltf, .obj or .png.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub run: DeriveRun,
    #[command(flatten)]
    pub look: LookArgs,
    #[command(flatten)]
    pub picture: PictureArgs,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum PailouTypeArg {
    Ridge,
    Pillar,
}

#[derive(Args, Debug)]
pub struct BuildArgs {
    #[command(flatten)]
    pub model: ModelArgs,
    /// The model to write; the extension picks the format: .glb, .gltf, .obj (+ .mtl beside it) or .png (a picture).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: PathBuf,
    #[command(flatten)]
    pub picture: PictureArgs,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    #[command(flatten)]
    pub model: ModelArgs,
    /// The picture to write (.png).
    #[arg(short = 'o', long = "output", value_name = "FILE.png")]
    pub output: PathBuf,
    #[command(flatten)]
    pub picture: PictureArgs,
    /// Shaded surfaces, or an architect's line drawing of the visible edges.
    #[arg(long, value_enum, default_value_t = Style::Shaded)]
    pub style: Style,
}

/// How a picture is taken.
#[derive(Args, Clone, Debug)]
pub struct PictureArgs {
    /// Where the camera looks from.
    #[arg(long, value_enum, default_value_t = View::Iso)]
    pub view: View,
    /// Set from `lsys render --style` (`lsys pailou` has its own `--style`).
    #[arg(skip)]
    pub style: Style,
    /// Picture size in pixels, WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH", default_value = "1024x768", value_parser = parse_size)]
    pub size: (u32, u32),
}

/// `--size`: the renderer's own parser, its message as clap's.
fn parse_size(s: &str) -> Result<(u32, u32), String> {
    crate::driver::parse_size(s).map_err(|e| {
        use miette::Diagnostic;
        match e.help() {
            Some(h) => format!("{e}; {h}"),
            None => e.to_string(),
        }
    })
}

/// A number that is finite (`--angle nan` would draw nothing sensible).
fn finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err("must be a finite number".to_string()),
        Err(e) => Err(e.to_string()),
    }
}

fn parse_define(s: &str) -> Result<(String, String), String> {
    match s.split_once('=') {
        Some((n, v)) if !n.trim().is_empty() && !v.trim().is_empty() => {
            Ok((n.trim().to_string(), v.trim().to_string()))
        }
        _ => Err(format!("`{s}` is not NAME=VALUE (e.g. -D NTL=7)")),
    }
}
