//! Load: a cpfg model's side files. The model's path in; its view file,
//! the turning angle the view file gives and the functions of its
//! `function:` and `function set:` lines out (`func(id, x)` numbers them
//! from 1 in that order), every file read added to the [`SourceMap`].
//!
//! cpfg is started with the view file on its command line; the model's
//! `specifications` file holds that line (`cpfg -M m.mat plant.l plant.v
//! plant.a`). Without it, the view file is the model's stem with `.v`.

use std::path::{Path, PathBuf};

use miette::Report;

use super::error::LoadError;
use super::include::IncludeFinder;
use super::surface::{self, CpfgSurface};
use crate::lang::spline::{parse_func, parse_gallery, SplineFn};
use crate::lang::Profile;
use crate::source::{FileId, Origin, SourceFile, SourceMap, Span};

/// What a model's view file gives, read while loading.
#[derive(Debug, Default)]
pub struct SideFiles {
    /// The view file, when there is one and it could be read.
    pub view: Option<FileId>,
    /// The turning angle of a cpfg model's view file (`angle factor: n`
    /// is 360/n degrees, `angle increment: d` is d degrees), computed in
    /// `f32` as cpfg reads it.
    pub angle: Option<f64>,
    /// The view file's functions, in `func` order.
    pub functions: ViewFunctions,
    /// The surfaces of its `surface: NAME FILE.s SIZE S T` lines (`~NAME`
    /// draws the surface), in file order, each file read and parsed.
    pub surfaces: Vec<CpfgSurface>,
    /// The colours of a cpfg model's colour map and material files (`-m`,
    /// `-M` in `specifications`): colour index and sRGB, later entries
    /// winning.
    pub colours: Vec<(usize, [f32; 3])>,
    /// The view file's `initial color:` (the turtle's first colour index).
    pub initial_colour: Option<u32>,
    /// How a cpfg model's lines are drawn (its view file's line width
    /// lines, else cpfg's defaults); `None` for other models.
    pub lines: Option<ViewLines>,
    /// The view file gives cpfg's bounding box (`box: x: ... y: ... z:
    /// ...`), which turns cpfg's automatic view volume off.
    pub view_box: bool,
    /// The contour curves of its `curve:` lines, in `curveX` order.
    pub curves: Vec<Result<crate::lang::curve::Curve, String>>,
    /// The cross-sections of its `contour:` lines (`@#(id)`).
    pub contours: Vec<super::contours::Contour>,
    /// Why `contour:` lines were left out.
    pub contour_problems: Vec<String>,
}

/// A cpfg view file's `initial line width: w [p]`, `line width
/// increment: d` and `line style:`, as cpfg reads them (interpret.c,
/// `ReadViewData`): without them lines are 1 pixel wide and `#`/`!`
/// without a parameter change nothing; `initial line width:` switches to
/// polygons (widths in the model's units) unless a `p` follows the number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewLines {
    pub width: f64,
    pub increment: f64,
    /// Widths are pixels on cpfg's screen, not model units.
    pub pixels: bool,
}

impl Default for ViewLines {
    fn default() -> ViewLines {
        ViewLines {
            width: 1.0,
            increment: 0.0,
            pixels: true,
        }
    }
}

/// The functions `func(id, x)` reads. Errors in the files are reported by
/// resolve when a `func` call needs them (a model that never calls `func`
/// compiles with a broken function file, as cpfg draws it).
#[derive(Debug, Default)]
pub enum ViewFunctions {
    /// The model has no view file.
    #[default]
    NoViewFile,
    /// The functions of its `function:` and `function set:` lines.
    Read(Vec<SplineFn>),
    /// Why they could not be read, each pointing at the line at fault.
    Failed(Vec<Report>),
}

/// Reads the side files of the model at `model`: the `specifications`
/// file beside it, the view file, the function files it names. The view
/// file's angle counts only for a cpfg model file; its functions count for
/// any model on disk (`func` is cpfg's, but a `.lsys` file may call it).
pub(super) fn read_side_files(
    model: &Path,
    profile: &Profile,
    finder: &IncludeFinder,
    sources: &mut SourceMap,
) -> SideFiles {
    let Some(view) = find_view_file(model, finder, sources) else {
        return SideFiles::default();
    };
    let text = match finder.read(&view) {
        Ok(t) => t,
        Err(r) => {
            let e = LoadError::ViewUnreadable {
                path: view.display().to_string(),
                why: r.message(),
            };
            return SideFiles {
                view: None,
                angle: None,
                functions: ViewFunctions::Failed(vec![Report::new(e)]),
                surfaces: Vec::new(),
                colours: Vec::new(),
                initial_colour: None,
                lines: profile.cpfg_model_file.then(ViewLines::default),
                view_box: false,
                curves: Vec::new(),
                contours: Vec::new(),
                contour_problems: Vec::new(),
            };
        }
    };
    let id = sources.add(SourceFile::new(
        view.display().to_string(),
        Origin::Disk(view.clone()),
        text,
    ));
    let angle = if profile.cpfg_model_file {
        view_angle(&sources.get(id).text)
    } else {
        None
    };
    let surfaces = surfaces(id, &view, finder, sources);
    let curves = super::curves::curves(id, &view, finder, sources);
    let (contours, contour_problems) = if profile.cpfg_model_file {
        super::contours::contours(id, &view, finder, sources)
    } else {
        Default::default()
    };
    SideFiles {
        curves,
        contours,
        contour_problems,
        view: Some(id),
        angle,
        functions: functions(id, &view, finder, sources),
        surfaces,
        colours: Vec::new(),
        initial_colour: initial_colour(&sources.get(id).text),
        lines: profile
            .cpfg_model_file
            .then(|| view_lines(&sources.get(id).text)),
        view_box: keyed_lines(&sources.get(id).text, "box").next().is_some(),
    }
}

/// The surfaces of a view file's `surface:` lines, each `.s` file read
/// (confined as includes are) and added to `sources`. A file that cannot
/// be read or parsed keeps the reason: cpfg then draws nothing for it.
fn surfaces(
    view_id: FileId,
    view: &Path,
    finder: &IncludeFinder,
    sources: &mut SourceMap,
) -> Vec<CpfgSurface> {
    let dir = view.parent().unwrap_or(Path::new("."));
    let text = sources.get(view_id).text.clone();
    let mut out = Vec::new();
    for rest in keyed_lines(&text, "surface") {
        let words: Vec<&str> = rest.split_whitespace().collect();
        let Some((name, file, size, s, t)) = surface::surface_line(&words) else {
            continue;
        };
        let path = dir.join(&file);
        let (patches, file_precision) = match finder.read(&path) {
            Ok(body) => {
                let id = sources.add(SourceFile::new(
                    path.display().to_string(),
                    Origin::Disk(path.clone()),
                    body,
                ));
                match surface::parse_surface(&sources.get(id).text, size) {
                    Ok((p, precision)) => (Ok(p), precision),
                    Err(e) => (Err(format!("{}: {e}", path.display())), None),
                }
            }
            Err(r) => (Err(r.message()), None),
        };
        let (s, t) = surface::precision((s, t), file_precision);
        out.push(CpfgSurface {
            name,
            file,
            s,
            t,
            patches,
        });
    }
    out
}

/// The words of each line of a `specifications` text that runs cpfg
/// (`cpfg -m plant.map plant.l plant.v`), in file order.
pub(super) fn cpfg_lines(text: &str) -> impl Iterator<Item = Vec<&str>> {
    text.lines()
        .map(|line| line.split_whitespace().collect::<Vec<&str>>())
        .filter(|words| words.iter().any(|w| *w == "cpfg" || w.ends_with("/cpfg")))
}

/// The text of the `specifications` file beside `model`, when
/// [`find_view_file`] read it into `sources`.
pub(super) fn specifications<'s>(model: &Path, sources: &'s SourceMap) -> Option<&'s str> {
    let dir = model.parent().unwrap_or(Path::new("."));
    let spec_path = dir.join("specifications");
    sources
        .files()
        .iter()
        .find(|f| f.origin == Origin::Disk(spec_path.clone()))
        .map(|f| f.text.as_str())
}

/// The view file cpfg would read for `model`, if there is one. A
/// `specifications` file that was read is added to `sources`.
fn find_view_file(
    model: &Path,
    finder: &IncludeFinder,
    sources: &mut SourceMap,
) -> Option<PathBuf> {
    let dir = model.parent().unwrap_or(Path::new("."));
    let spec_path = dir.join("specifications");
    if spec_path.is_file() {
        if let Ok(spec) = finder.read(&spec_path) {
            let id = sources.add(SourceFile::new(
                spec_path.display().to_string(),
                Origin::Disk(spec_path.clone()),
                spec,
            ));
            for words in cpfg_lines(&sources.get(id).text) {
                if let Some(v) = words.iter().find(|w| w.ends_with(".v")) {
                    let p = dir.join(v);
                    if p.is_file() {
                        return Some(p);
                    }
                }
            }
        }
    }
    let stem = model.with_extension("v");
    stem.is_file().then_some(stem)
}

/// The functions of the view file `view_id` (at `view`), each function
/// file added to `sources`.
fn functions(
    view_id: FileId,
    view: &Path,
    finder: &IncludeFinder,
    sources: &mut SourceMap,
) -> ViewFunctions {
    let dir = view.parent().unwrap_or(Path::new("."));
    let text = sources.get(view_id).text.clone();
    let mut out = Vec::new();
    let mut errors = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let Some((key, rest)) = line.split_once(':') else {
            continue;
        };
        let key = key.trim().to_ascii_lowercase();
        let gallery = match key.as_str() {
            "function" => false,
            "function set" | "functions" => true,
            _ => continue,
        };
        let at = line_span(sources.get(view_id), view_id, i + 1);
        let Some(file) = rest.split_whitespace().next() else {
            errors.push(Report::new(LoadError::ViewFile {
                why: format!("`{key}:` names no file"),
                src: sources.get(view_id).named_source(),
                span: at.into(),
                help: Some(format!("write `{key}: FILE`")),
            }));
            continue;
        };
        let path = dir.join(file);
        let body = match finder.read(&path) {
            Ok(b) => b,
            Err(r) => {
                errors.push(Report::new(LoadError::ViewFile {
                    why: format!("cannot use the function file {}", path.display()),
                    src: sources.get(view_id).named_source(),
                    span: at.into(),
                    help: Some(r.message()),
                }));
                continue;
            }
        };
        let id = sources.add(SourceFile::new(
            path.display().to_string(),
            Origin::Disk(path.clone()),
            body,
        ));
        let body = sources.get(id);
        let parsed = if gallery {
            parse_gallery(&body.text)
        } else {
            let samples = rest
                .split_whitespace()
                .nth(1)
                .and_then(|n| n.parse().ok())
                .unwrap_or(0);
            parse_func(&body.text, samples).map(|f| vec![f])
        };
        match parsed {
            Ok(fs) => out.extend(fs),
            Err(e) => errors.push(Report::new(LoadError::FunctionFile {
                path: path.display().to_string(),
                why: e.message,
                src: body.named_source(),
                span: line_span(body, id, e.line).into(),
            })),
        }
    }
    if errors.is_empty() {
        ViewFunctions::Read(out)
    } else {
        ViewFunctions::Failed(errors)
    }
}

/// The colour index a view file's `initial color:` line gives.
fn initial_colour(text: &str) -> Option<u32> {
    text.lines().find_map(|line| {
        let (key, rest) = line.split_once(':')?;
        let key = key.trim().to_ascii_lowercase();
        (key == "initial color" || key == "initial colour")
            .then(|| rest.split_whitespace().next()?.parse::<f64>().ok())
            .flatten()
            .map(|c| c.max(0.0) as u32)
    })
}

/// What follows `key:` on each of a view file's lines that start with it
/// (in either case), in order.
pub(super) fn keyed_lines<'a>(text: &'a str, key: &'a str) -> impl Iterator<Item = &'a str> {
    text.lines().filter_map(move |line| {
        let (k, rest) = line.split_once(':')?;
        k.trim().eq_ignore_ascii_case(key).then_some(rest)
    })
}

/// The line settings of a view file's text; later lines win, as cpfg
/// reads them in order.
fn view_lines(text: &str) -> ViewLines {
    let mut lines = ViewLines::default();
    for line in text.lines() {
        let Some((key, rest)) = line.split_once(':') else {
            continue;
        };
        let mut words = rest.split_whitespace();
        let first = words.next().unwrap_or("");
        match key.trim().to_ascii_lowercase().as_str() {
            "initial line width" => {
                if let Ok(w) = first.parse::<f32>() {
                    lines.width = f64::from(w);
                    lines.pixels = words.next().is_some_and(|u| u.starts_with('p'));
                }
            }
            "line width increment" => {
                if let Ok(d) = first.parse::<f32>() {
                    lines.increment = f64::from(d);
                }
            }
            "line style" => {
                lines.pixels = first == "pixel" || first == "1";
            }
            _ => {}
        }
    }
    lines
}

/// The turning angle a view file's text gives, computed in `f32` as cpfg
/// reads it. `None` without either line.
fn view_angle(text: &str) -> Option<f64> {
    let mut angle = None;
    for line in text.lines() {
        let Some((key, rest)) = line.split_once(':') else {
            continue;
        };
        let value = rest
            .split_whitespace()
            .next()
            .and_then(|v| v.parse::<f32>().ok());
        match (key.trim().to_ascii_lowercase().as_str(), value) {
            ("angle factor", Some(n)) if n != 0.0 => angle = Some(f64::from(360.0f32 / n)),
            ("angle increment", Some(d)) => angle = Some(f64::from(d)),
            _ => {}
        }
    }
    angle
}

/// The line of a view file that says `angle factor: 0` (360° / 0 is no
/// angle, so the file's angle is ignored), if any.
pub(super) fn zero_angle_factor(file: &SourceFile, id: FileId) -> Option<Span> {
    file.text.lines().enumerate().find_map(|(n, line)| {
        let (key, rest) = line.split_once(':')?;
        let value = rest.split_whitespace().next()?.parse::<f32>().ok()?;
        (key.trim().eq_ignore_ascii_case("angle factor") && value == 0.0)
            .then(|| line_span(file, id, n + 1))
    })
}

/// The span of 1-based line `line` of `file` (without its line break); an
/// empty span at the end for a line past the end.
fn line_span(file: &SourceFile, id: FileId, line: usize) -> Span {
    let text = file.text.as_str();
    let mut start = 0;
    for (n, l) in text.split_inclusive('\n').enumerate() {
        if n + 1 == line {
            let body = l.trim_end_matches(['\n', '\r']);
            return Span::new(id, start, start + body.len());
        }
        start += l.len();
    }
    Span::new(id, text.len(), text.len())
}
