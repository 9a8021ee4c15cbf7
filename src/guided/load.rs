//! A scene file on disk in, a [`Loaded`] scene out: the checked
//! [`SceneSpec`] and every grammar it names compiled once (paths relative
//! to the scene file, or `std:NAME`).

use std::path::{Path, PathBuf};
use std::sync::Arc;

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

/// Reads and compiles a scene file.
pub fn load_file(path: &Path, opts: &crate::load::Options) -> Result<Loaded, Box<SceneError>> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        Box::new(SceneError::Syntax {
            file: path.display().to_string(),
            message: format!("cannot read it: {e}"),
            src: NamedSource::new(path.display().to_string(), Arc::new(String::new())),
            span: None,
        })
    })?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    load_text(&path.display().to_string(), &text, &base, opts)
}

/// Reads and compiles a scene's text, grammars relative to `base`.
pub fn load_text(
    name: &str,
    text: &str,
    base: &Path,
    opts: &crate::load::Options,
) -> Result<Loaded, Box<SceneError>> {
    let spec = scene::read(name, text)?;
    let src = NamedSource::new(name, Arc::new(text.to_string()));
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
