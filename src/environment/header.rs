//! The `environment:` header of a `.lsys` file: `NAME` or `NAME(key:
//! value, ...)` in; the [`EnvironmentSpec`] it selects out. Names are the
//! programs' own (`collision` or `honda81`, `light` or `chiba`) and keys
//! are those of the program's specification file (`radius`, `3d case`,
//! `transmittance`, `source direction`, ...), so a cpfg model's settings
//! carry over. The turtle's position, heading, left and up are sent
//! unrounded (a `.lsys` file has no communication file to format them).

use miette::{NamedSource, SourceSpan};

use super::communication::{EnvironmentSpec, Field, FieldKind, Settings};
use super::error::EnvironmentError;
use super::{clover, collision, density, light};

/// The names the header accepts, and the vlab program each is.
pub const NAMES: [(&str, &str); 6] = [
    ("collision", "honda81"),
    ("honda81", "honda81"),
    ("light", "chiba"),
    ("chiba", "chiba"),
    ("density", "density"),
    ("clover", "clover"),
];

/// Reads the header's text (what follows `environment:`), which starts at
/// `span` in `src`.
pub fn environment_header(
    text: &str,
    images: &[(String, crate::load::HeaderImage)],
    src: NamedSource<crate::source::SourceText>,
    span: SourceSpan,
) -> Result<EnvironmentSpec, Box<EnvironmentError>> {
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
        "clover" => {
            // An image that could not be read is reported here, at the
            // header that names it, rather than as "not loaded".
            let mut loaded = Vec::new();
            for (name, read) in images {
                match read {
                    Ok(bytes) => loaded.push((name.clone(), bytes.clone())),
                    Err(why) if args.contains(name.as_str()) => {
                        return Err(Box::new(EnvironmentError::BadValue {
                            key: "input image".into(),
                            why: why.clone(),
                            src,
                            span,
                            help: Some(
                                "the image is read relative to the grammar's folder; \
                                 lsys reads SGI `.rgb` images"
                                    .into(),
                            ),
                        }))
                    }
                    Err(_) => {}
                }
            }
            Settings::Clover(clover::Settings::read(&spec, &loaded, bad)?)
        }
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
    Ok(EnvironmentSpec { settings, fields })
}
