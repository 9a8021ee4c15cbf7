//! A scene file on disk in, a [`Loaded`] scene out: the checked
//! [`SceneSpec`] and every grammar it names compiled once (paths relative
//! to the scene file, or `std:NAME`).

use std::path::{Path, PathBuf};

use miette::NamedSource;

use super::scene::{self, SceneError, SceneSpec};
use crate::load::Input;
use crate::pipeline::{self, Compilation};

/// A scene with its grammars compiled.
pub struct Loaded {
    pub spec: SceneSpec,
    /// Distinct grammars, in the order first named.
    pub grammars: Vec<Compilation>,
    pub grammar_names: Vec<String>,
    /// Per guide, per explicit seed: an index into `grammars`.
    pub guide_grammar: Vec<usize>,
    pub seed_grammar: Vec<usize>,
}

/// Reads and compiles a scene file. Its grammars must be inside the
/// scene's folder, an `--include-dir` or one of `component_dirs` (links
/// followed), as includes must (docs/limits.md).
pub fn load_file(
    path: &Path,
    opts: &crate::load::Options,
    component_dirs: &[PathBuf],
) -> Result<Loaded, Box<SceneError>> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        Box::new(SceneError::Syntax {
            file: path.display().to_string(),
            message: format!("cannot read it: {e}"),
            src: NamedSource::new(
                path.display().to_string(),
                crate::source::SourceText::from(String::new()),
            ),
            span: None,
        })
    })?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut allowed = vec![if base.as_os_str().is_empty() {
        PathBuf::from(".")
    } else {
        base.clone()
    }];
    allowed.extend(opts.include_dirs.iter().cloned());
    allowed.extend(component_dirs.iter().cloned());
    load_confined(
        &path.display().to_string(),
        &text,
        &base,
        opts,
        Some(&allowed),
    )
}

/// Reads and compiles a scene's text, grammars relative to `base`.
pub fn load_text(
    name: &str,
    text: &str,
    base: &Path,
    opts: &crate::load::Options,
) -> Result<Loaded, Box<SceneError>> {
    load_confined(name, text, base, opts, None)
}

/// [`load_text`] with every grammar file required to resolve (links
/// followed) inside one of `allowed` (the studio's folder).
pub fn load_text_within(
    name: &str,
    text: &str,
    base: &Path,
    opts: &crate::load::Options,
    allowed: &[PathBuf],
) -> Result<Loaded, Box<SceneError>> {
    load_confined(name, text, base, opts, Some(allowed))
}

/// [`load_text`], with every grammar file required to resolve (links
/// followed) inside one of `allowed`, when given: a scene from someone
/// else cannot have `../../etc/passwd` compiled and its lines shown.
fn load_confined(
    name: &str,
    text: &str,
    base: &Path,
    opts: &crate::load::Options,
    allowed: Option<&[PathBuf]>,
) -> Result<Loaded, Box<SceneError>> {
    // Missing folders allow nothing: they cannot be canonicalised.
    let roots: Vec<PathBuf> = allowed
        .unwrap_or_default()
        .iter()
        .filter_map(|d| std::fs::canonicalize(d).ok())
        .collect();
    let spec = scene::read(name, text)?;
    let src = NamedSource::new(name, crate::source::SourceText::from(text.to_string()));
    let mut l = Loaded {
        spec: spec.clone(),
        grammars: Vec::new(),
        grammar_names: Vec::new(),
        guide_grammar: Vec::new(),
        seed_grammar: Vec::new(),
    };
    let mut index = |g: &str, span: &std::ops::Range<usize>| -> Result<usize, Box<SceneError>> {
        if let Some(i) = l.grammar_names.iter().position(|n| n == g) {
            return Ok(i);
        }
        let input = match g.strip_prefix("std:") {
            Some(n) => Input::Std(n.to_string()),
            None => Input::Path(resolve_path(base, g)),
        };
        if let (Input::Path(p), Some(allowed)) = (&input, allowed) {
            // A file that does not resolve is left to the compiler, which
            // says it is missing; one that does is checked before a byte of
            // it is read.
            if let Ok(real) = std::fs::canonicalize(p) {
                if !roots.iter().any(|r| real.starts_with(r)) {
                    let inside = allowed
                        .iter()
                        .map(|d| d.display().to_string())
                        .collect::<Vec<_>>()
                        .join(" or ");
                    return Err(Box::new(SceneError::Outside {
                        grammar: g.to_string(),
                        src: src.clone(),
                        span: span.clone().into(),
                        help: format!(
                            "{} is not inside {inside} (links are followed); copy the grammar into the scene's folder, or allow its folder with `--include-dir DIR` or `--components DIR`",
                            p.display()
                        ),
                    }));
                }
            }
        }
        let comp = pipeline::compile(&input, opts).map_err(|d| {
            Box::new(SceneError::Grammar {
                grammar: g.to_string(),
                src: src.clone(),
                span: span.clone().into(),
                details: d.render_plain(),
            })
        })?;
        l.grammars.push(comp);
        l.grammar_names.push(g.to_string());
        Ok(l.grammars.len() - 1)
    };
    let mut guide_grammar = Vec::new();
    for g in &spec.guides {
        guide_grammar.push(index(&g.grammar, &g.grammar_span)?);
    }
    let mut seed_grammar = Vec::new();
    for s in &spec.seeds {
        seed_grammar.push(match &s.grammar {
            Some((g, span)) => index(g, span)?,
            None => guide_grammar[s.guide],
        });
    }
    l.guide_grammar = guide_grammar;
    l.seed_grammar = seed_grammar;
    Ok(l)
}

fn resolve_path(base: &Path, g: &str) -> PathBuf {
    let p = PathBuf::from(g);
    if p.is_absolute() {
        p
    } else {
        base.join(p)
    }
}
