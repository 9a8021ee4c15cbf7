//! The `environment:` header of a `.lsys` file: `NAME` or `NAME(key:
//! value, ...)` in; the [`Environment`] it selects out. Names are the
//! programs' own (`collision` or `honda81`, `light` or `chiba`) and keys
//! are those of the program's specification file (`radius`, `3d case`,
//! `transmittance`, `source direction`, ...), so a cpfg model's settings
//! carry over. The turtle's position, heading, left and up are sent
//! unrounded (a `.lsys` file has no communication file to format them).

use std::sync::Arc;

use miette::{NamedSource, SourceSpan};

use super::communication::{Environment, Field, FieldKind, Settings};
use super::error::EnvironmentError;
use super::{collision, density, light};

/// The names the header accepts, and the vlab program each is.
pub const NAMES: [(&str, &str); 5] = [
    ("collision", "honda81"),
    ("honda81", "honda81"),
    ("light", "chiba"),
    ("chiba", "chiba"),
    ("density", "density"),
];

/// Reads the header's text (what follows `environment:`), which starts at
/// `span` in `src`.
pub fn environment_header(
    text: &str,
    src: NamedSource<Arc<String>>,
    span: SourceSpan,
) -> Result<Environment, Box<EnvironmentError>> {
    let trimmed = text.trim();
    let (name, args) = match trimmed.split_once('(') {
        Some((n, rest)) => {
            let Some(args) = rest.trim_end().strip_suffix(')') else {
                return Err(Box::new(EnvironmentError::BadValue {
                    key: "environment".into(),
                    why: "the settings' `(` is not closed".into(),
                    src,
                    span,
                    help: Some(
                        "write e.g. `environment: collision(radius: 0.01, 3d case: on)`".into(),
                    ),
                }));
            };
            (n.trim(), args)
        }
        None => (trimmed, ""),
    };
    let Some(&(_, program)) = NAMES.iter().find(|(n, _)| *n == name) else {
        let known: Vec<&str> = NAMES.iter().map(|(n, _)| *n).collect();
        return Err(Box::new(EnvironmentError::UnknownProgram {
            name: name.to_string(),
            known: known.join(", "),
            src,
            span,
        }));
    };
    // `key: value, key: value` as the specification file's lines. A
    // `source direction` takes several numbers, so split at commas only
    // before a `key:`.
    let mut spec = String::new();
    for part in args.split(',') {
        if part.contains(':') || spec.is_empty() {
            spec.push('\n');
        } else {
            spec.push(' ');
        }
        spec.push_str(part.trim());
    }
    let bad = |key: &str, _: SourceSpan, why: String| {
        Box::new(EnvironmentError::BadValue {
            key: key.to_string(),
            why,
            src: src.clone(),
            span,
            help: None,
        })
    };
    let settings = match program {
        "honda81" => Settings::Collision(collision::Settings::read(&spec, bad)?),
        "density" => Settings::Density(density::Settings::read(&spec, bad)?),
        _ => Settings::Light(light::Settings::read(&spec, bad)?),
    };
    let fields = [
        FieldKind::Position,
        FieldKind::Heading,
        FieldKind::Left,
        FieldKind::Up,
    ]
    .into_iter()
    .map(|kind| Field {
        kind,
        conversions: Vec::new(),
    })
    .collect();
    Ok(Environment { settings, fields })
}
