//! Load: a cpfg model's environment files. The model's path and its
//! `specifications` (already read) in; the communication file (`.e`) that
//! cpfg's `-e FILE` names and the specification file its `executable:`
//! line gives the environmental program, each added to the [`SourceMap`]
//! out. Reading them here keeps resolve and the simulation free of I/O;
//! what they say is read by `crate::environment`.

use std::path::Path;

use miette::Report;

use super::error::LoadError;
use super::include::IncludeFinder;
use crate::parse::ast::{HeaderKind, Item};
use crate::source::{FileId, Origin, SourceFile, SourceMap};

/// A model's environment files, as loaded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EnvironmentFiles {
    /// The communication file (`fractal.e`): the program and the turtle
    /// fields it is sent.
    pub communication: FileId,
    /// The program's specification file (`density.spec`), when the
    /// `executable:` line names one that could be read.
    pub specification: Option<FileId>,
    /// The binary files the specification names (`input image: X.rgb`),
    /// as the name written there and their bytes.
    pub data: Vec<(String, std::sync::Arc<Vec<u8>>)>,
}

/// The environment files of `model`, if its `specifications` runs cpfg
/// with `-e FILE`. Errors name the file that could not be read.
pub(super) fn read_environment_files(
    model: &Path,
    finder: &IncludeFinder,
    sources: &mut SourceMap,
) -> (Option<EnvironmentFiles>, Vec<Report>) {
    let dir = model.parent().unwrap_or(Path::new("."));
    let Some(spec) = super::view::specifications(model, sources) else {
        return (None, Vec::new());
    };
    let e_name = super::view::cpfg_lines(spec).find_map(|words| {
        let at = words.iter().position(|w| *w == "-e")?;
        words.get(at + 1).map(|w| w.to_string())
    });
    let Some(e_name) = e_name else {
        return (None, Vec::new());
    };
    let mut errors = Vec::new();
    let e_path = dir.join(&e_name);
    let e_text = match finder.read(&e_path) {
        Ok(t) => t,
        Err(r) => {
            errors.push(Report::new(LoadError::EnvironmentUnreadable {
                path: e_path.display().to_string(),
                why: r.message(),
            }));
            return (None, errors);
        }
    };
    let communication = sources.add(SourceFile::new(
        e_path.display().to_string(),
        Origin::Disk(e_path.clone()),
        e_text,
    ));
    // `executable: PROGRAM [-e FILE.e] SPECFILE`: the specification file
    // is the last word, when there is one besides the program.
    let spec_name = sources.get(communication).text.lines().find_map(|line| {
        let (key, rest) = line.split_once(':')?;
        if !key.trim().eq_ignore_ascii_case("executable") {
            return None;
        }
        let words: Vec<&str> = rest.split_whitespace().collect();
        (words.len() > 1).then(|| words[words.len() - 1].to_string())
    });
    let specification = spec_name.and_then(|name| {
        let path = dir.join(&name);
        match finder.read(&path) {
            Ok(text) => Some(sources.add(SourceFile::new(
                path.display().to_string(),
                Origin::Disk(path.clone()),
                text,
            ))),
            Err(r) => {
                errors.push(Report::new(LoadError::EnvironmentUnreadable {
                    path: path.display().to_string(),
                    why: r.message(),
                }));
                None
            }
        }
    });
    // Binary inputs of the program (clover's `input image:`).
    let mut data = Vec::new();
    if let Some(spec) = specification {
        let names: Vec<String> = sources
            .get(spec)
            .text
            .lines()
            .filter_map(|l| {
                let (k, v) = l.split_once(':')?;
                (k.trim() == "input image")
                    .then(|| v.split([',', ';', ' ', '\t']).find(|w| !w.is_empty()))
                    .flatten()
                    .map(str::to_string)
            })
            .collect();
        for name in names {
            let path = dir.join(&name);
            match finder.read_bytes(&path) {
                Ok(bytes) => data.push((name, std::sync::Arc::new(bytes))),
                Err(r) => errors.push(Report::new(LoadError::EnvironmentUnreadable {
                    path: path.display().to_string(),
                    why: r.message(),
                })),
            }
        }
    }
    (
        Some(EnvironmentFiles {
            communication,
            specification,
            data,
        }),
        errors,
    )
}

/// The `input image:` files named by the `environment:` headers of
/// `items` and by the `--environment` option (clover's light image), read
/// relative to the folder of the file that names them (the option's,
/// relative to the root file's folder): the name as written and the bytes,
/// or why they could not be read (the header reports it at its own span).
pub(super) fn read_header_images(
    items: &[(FileId, Item)],
    option: Option<&str>,
    root_dir: &Path,
    finder: &IncludeFinder,
    sources: &SourceMap,
) -> Vec<(String, HeaderImage)> {
    let headers = items.iter().filter_map(|(file, item)| match item {
        Item::Header(h) => match &h.kind {
            HeaderKind::Environment(text, _) => {
                let dir = match &sources.get(*file).origin {
                    Origin::Disk(p) => p.parent().map(Path::to_path_buf),
                    _ => None,
                };
                Some((text.as_str(), dir.unwrap_or_else(|| root_dir.to_path_buf())))
            }
            _ => None,
        },
        _ => None,
    });
    let mut data: Vec<(String, HeaderImage)> = Vec::new();
    for (text, dir) in headers.chain(option.map(|o| (o, root_dir.to_path_buf()))) {
        // `clover(input image: light.rgb, transmittance: 0.4)`: the name
        // runs to the next `,` or `)`.
        let Some((_, rest)) = text.split_once("input image:") else {
            continue;
        };
        let name = rest.split([',', ')']).next().unwrap_or("").trim();
        if name.is_empty() || data.iter().any(|(n, _)| n == name) {
            continue;
        }
        let path = dir.join(name);
        let read = finder
            .read_bytes(&path)
            .map(std::sync::Arc::new)
            .map_err(|r| r.message());
        data.push((name.to_string(), read));
    }
    data
}

/// An image an `environment:` header names: its bytes, or why not.
pub type HeaderImage = Result<std::sync::Arc<Vec<u8>>, String>;
