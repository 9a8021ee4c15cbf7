//! Hover. Input: an [`Analysis`] and a byte offset in the root document;
//! output: Markdown about the name there: a module's productions and
//! parameter names, a `#define`'s text and the value in force (after `-D`
//! overrides), a turtle command's meaning and parameters (the command
//! table of [`crate::lang::commands`]), a parameter's production, a
//! component's source, an include's file.

use std::fmt::Write;
use std::path::PathBuf;

use super::analysis::Analysis;
use super::index::{formal_params, Kind, Occ};
use crate::lang;
use crate::parse::ast::Item;
use crate::source::Span;
use crate::stdlib;

/// Productions listed in a hover before "and N more".
const MAX_LISTED: usize = 12;

pub fn hover(a: &Analysis, occ: &Occ) -> Option<String> {
    let mut out = String::new();
    match occ.kind {
        Kind::Define => define(a, occ, &mut out),
        Kind::Module | Kind::Turtle => module(a, occ, &mut out),
        Kind::Query => {
            let _ = write!(
                out,
                "query module `{}`: its parameters are filled in by the turtle after each step (position, heading, left, up)",
                occ.name
            );
        }
        Kind::Param => param(a, occ, &mut out),
        Kind::Component => component(a, occ, &mut out),
        Kind::Include => {
            let f = a.sources.get(occ.target?);
            let lines = f.text.lines().count();
            let _ = write!(out, "includes `{}` ({lines} lines)", f.name);
        }
    }
    (!out.is_empty()).then_some(out)
}

fn code_block(out: &mut String, text: &str) {
    let _ = write!(out, "```lsys\n{}\n```\n", text.trim_end());
}

fn define(a: &Analysis, occ: &Occ, out: &mut String) {
    for d in a.index.definitions(occ) {
        if let Some(stmt) = d.stmt {
            code_block(out, &statement_text(a, stmt));
        }
    }
    let info = a
        .program()
        .and_then(|p| p.defines.iter().find(|d| d.name == occ.name));
    if let Some(info) = info {
        match (info.value, info.overridden) {
            (Some(v), true) => {
                let _ = writeln!(out, "value in force: `{v}` (overridden with `-D`)");
            }
            (Some(v), false) => {
                let _ = writeln!(out, "value: `{v}`");
            }
            _ => {}
        }
    }
    if out.is_empty() {
        let _ = write!(out, "`#define {}`", occ.name);
    }
}

/// A `#define` statement: `#define NAME value` (a list form shows its item).
fn statement_text(a: &Analysis, stmt: Span) -> String {
    let text = a.sources.slice(stmt).trim();
    if text.starts_with("#define") {
        text.to_string()
    } else {
        format!("#define {text}")
    }
}

fn module(a: &Analysis, occ: &Occ, out: &mut String) {
    if occ.kind == Kind::Turtle {
        if let Some(c) = lang::lookup(&occ.name) {
            let params = match (c.min_args, c.max_args) {
                (0, 0) => "no parameters".to_string(),
                (lo, hi) if lo == hi => format!("{lo} parameter{}", if lo == 1 { "" } else { "s" }),
                (lo, hi) => format!("{lo} to {hi} parameters"),
            };
            let _ = writeln!(out, "**`{}`** — turtle command: {}\n", c.symbol, c.doc);
            let _ = write!(out, "{params}");
            if !c.default.is_empty() {
                let _ = write!(out, "; without one: {}", c.default);
            }
            out.push('\n');
            if c.paper != c.cpfg {
                let _ = writeln!(
                    out,
                    "\n(the meaning depends on the dialect; this file is `{}`)",
                    a.profile.dialect.name()
                );
            }
        }
    }
    let prods: Vec<&Occ> = a.index.definitions(occ).collect();
    if prods.is_empty() {
        if occ.kind == Kind::Module {
            let _ = writeln!(out, "module `{}`: no production rewrites it", occ.name);
        }
        return;
    }
    if occ.kind == Kind::Module {
        let _ = writeln!(out, "**`{}`** — module", occ.name);
    }
    let mut params: Vec<Vec<String>> = Vec::new();
    let mut listed = 0;
    let mut text = String::new();
    for d in &prods {
        let Some(stmt) = d.stmt else {
            // A `module` declaration.
            continue;
        };
        if let Some((_, Item::Production(p))) = a
            .items
            .iter()
            .find(|(_, i)| matches!(i, Item::Production(p) if p.span == stmt))
        {
            for (name, ps) in formal_params(p) {
                if name == occ.name && !ps.is_empty() && !params.contains(&ps) {
                    params.push(ps);
                }
            }
        }
        if listed < MAX_LISTED {
            let _ = writeln!(text, "{}", a.sources.slice(stmt).trim());
        }
        listed += 1;
    }
    for ps in &params {
        let _ = writeln!(out, "\nparameters: `{}({})`", occ.name, ps.join(", "));
    }
    if !text.is_empty() {
        let n = listed;
        let _ = writeln!(out, "\n{n} production{}:", if n == 1 { "" } else { "s" });
        code_block(out, &text);
        if n > MAX_LISTED {
            let _ = writeln!(out, "and {} more", n - MAX_LISTED);
        }
    }
}

fn param(a: &Analysis, occ: &Occ, out: &mut String) {
    let def = a.index.definitions(occ).next();
    let stmt = def.and_then(|d| {
        a.items
            .iter()
            .filter(|(f, _)| *f == d.span.file)
            .find_map(|(_, i)| match i {
                Item::Production(p) if p.span.start <= d.span.start && d.span.end <= p.span.end => {
                    Some(p.head_span)
                }
                _ => None,
            })
    });
    let _ = write!(out, "parameter `{}`", occ.name);
    if let Some(head) = stmt {
        let _ = write!(out, " of `{}`", a.sources.slice(head).trim());
    }
}

/// Where component `name` comes from, as `build` looks it up (a file in
/// `components/` beside the grammar, a roof, a built-in OBJ model, a
/// standard library grammar), and the file an editor can open for it.
pub fn component_source(a: &Analysis, name: &str) -> (String, Option<PathBuf>) {
    let dir = a
        .uri
        .to_file_path()
        .ok()
        .and_then(|p| p.parent().map(|d| d.join("components")));
    for ext in ["obj", "lsys"] {
        if let Some(p) = dir
            .as_ref()
            .map(|d| d.join(format!("{name}.{ext}")))
            .filter(|p| p.is_file())
        {
            return (
                format!("`components/{name}.{ext}` beside the grammar"),
                Some(p),
            );
        }
    }
    if a.program()
        .is_some_and(|p| p.cpfg_surfaces.iter().any(|s| s.name == name))
    {
        return ("a surface the model's view file names".into(), None);
    }
    if crate::mesh::roof::RoofKind::from_name(name).is_some() {
        return ("a roof, built when the model is".into(), None);
    }
    if let Some(text) = stdlib::component(name) {
        let file = cached_component(name, text);
        return (
            format!("the built-in OBJ model `grammar/std/components/{name}.obj`"),
            file,
        );
    }
    if let Some(g) = stdlib::grammar_component(name) {
        return (
            format!("the standard library grammar `std:{g}`, derived once and placed"),
            super::analysis::std_file(g),
        );
    }
    (
        format!("not found beside the grammar (`components/{name}.obj`) nor built in; `build` also looks in `--components` folders"),
        None,
    )
}

/// A built-in component's OBJ text as a file in the cache folder.
fn cached_component(name: &str, text: &str) -> Option<PathBuf> {
    let dir = std::env::temp_dir().join(format!("lsys-std-{}", env!("CARGO_PKG_VERSION")));
    let path = dir.join(format!("{name}.obj"));
    if std::fs::read_to_string(&path).ok().as_deref() != Some(text) {
        std::fs::create_dir_all(&dir).ok()?;
        std::fs::write(&path, text).ok()?;
    }
    Some(path)
}

fn component(a: &Analysis, occ: &Occ, out: &mut String) {
    let name = &occ.name;
    let (source, _) = component_source(a, name);
    let _ = write!(out, "component `~{name}`: {source}");
    if a.index.definitions(occ).next().is_some() {
        let _ = write!(out, "\n\ndeclared with `#include {name}`");
    }
}
