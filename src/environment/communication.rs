//! A cpfg communication file (`.e`) and its program's specification file
//! in; the [`EnvironmentSpec`] a simulation runs out: which program answers
//! `?E`, with which settings, and which turtle fields it is sent in which
//! format. Unknown programs and unreadable values are diagnostics that
//! point at the line.

use miette::SourceSpan;

use super::error::EnvironmentError;
use super::format::Conversion;
use super::{clover, collision, density, light, EnvironmentalProgram};
use crate::load::EnvironmentFiles;
use crate::source::SourceMap;

/// The environmental programs lsys runs, by their vlab names.
pub const PROGRAMS: [&str; 4] = ["honda81", "chiba", "density", "clover"];

/// A turtle field sent with each query, with its format's conversions.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    pub kind: FieldKind,
    pub conversions: Vec<Conversion>,
}

/// Which turtle field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FieldKind {
    Position,
    Heading,
    Left,
    Up,
    LineWidth,
    ScaleFactor,
}

impl FieldKind {
    fn from_key(key: &str) -> Option<FieldKind> {
        Some(match key {
            "turtle position" => FieldKind::Position,
            "turtle heading" => FieldKind::Heading,
            "turtle left" => FieldKind::Left,
            "turtle up" => FieldKind::Up,
            "turtle line width" => FieldKind::LineWidth,
            "turtle scale factor" => FieldKind::ScaleFactor,
            _ => return None,
        })
    }
}

/// The program and its settings.
#[derive(Clone, Debug, PartialEq)]
pub enum Settings {
    Collision(collision::Settings),
    Light(light::Settings),
    Clover(clover::Settings),
    Density(density::Settings),
}

/// An environment as configured by a model's files: what a simulation
/// needs to run environment passes.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvironmentSpec {
    pub settings: Settings,
    /// The turtle fields each query carries.
    pub fields: Vec<Field>,
}

impl EnvironmentSpec {
    /// A fresh program with these settings (programs keep no state
    /// between passes, but each simulation gets its own).
    pub fn program(&self) -> Box<dyn EnvironmentalProgram> {
        match &self.settings {
            Settings::Collision(s) => Box::new(collision::Collision::new(s.clone())),
            Settings::Light(s) => Box::new(light::Light::new(s.clone())),
            Settings::Clover(s) => Box::new(clover::Clover::new(s.clone())),
            Settings::Density(s) => Box::new(density::Density::new(s.clone())),
        }
    }

    /// Whether a field is sent, and with which conversions.
    pub fn field(&self, kind: FieldKind) -> Option<&[Conversion]> {
        self.fields
            .iter()
            .find(|f| f.kind == kind)
            .map(|f| f.conversions.as_slice())
    }
}

/// One `key: value` line of a cpfg settings file, with where its value is.
pub(super) struct Line<'a> {
    pub key: String,
    pub value: &'a str,
    pub span: SourceSpan,
}

/// The `key: value` lines of `text` (keys lower-cased, trimmed).
pub(super) fn lines(text: &str) -> Vec<Line<'_>> {
    let mut out = Vec::new();
    let mut at = 0;
    for raw in text.split_inclusive('\n') {
        let line = raw.trim_end_matches(['\n', '\r']);
        if let Some((key, value)) = line.split_once(':') {
            let start = at + key.len() + 1;
            out.push(Line {
                key: key.trim().to_ascii_lowercase(),
                value,
                span: SourceSpan::new(start.into(), value.len()),
            });
        }
        at += raw.len();
    }
    out
}

/// Reads the communication file `communication` and the specification
/// file `specification` of `sources` into an [`EnvironmentSpec`].
pub fn configure(
    sources: &SourceMap,
    files: &EnvironmentFiles,
) -> Result<EnvironmentSpec, Box<EnvironmentError>> {
    let (communication, specification) = (files.communication, files.specification);
    let file = sources.get(communication);
    let text = file.text.as_str();
    let mut program = None;
    let mut fields = Vec::new();
    for line in lines(text) {
        if line.key == "executable" {
            let name = line.value.split_whitespace().next().unwrap_or_default();
            let offset = line.value.find(name).unwrap_or(0);
            program = Some((
                name.to_string(),
                SourceSpan::new((line.span.offset() + offset).into(), name.len()),
            ));
        } else if let Some(kind) = FieldKind::from_key(&line.key) {
            // `turtle position:P:%.4f %.4f %.0f`: a tag, then the format.
            let format = line.value.split_once(':').map_or(line.value, |(_, f)| f);
            let conversions = Conversion::parse_all(format).ok_or_else(|| {
                Box::new(EnvironmentError::BadValue {
                    key: line.key.clone(),
                    why: format!("`{}` is not a printf format of numbers", format.trim()),
                    src: file.named_source(),
                    span: line.span,
                    help: Some("write e.g. `turtle position:P:%.4f %.4f %.4f`".into()),
                })
            })?;
            fields.push(Field { kind, conversions });
        }
    }
    let Some((name, span)) = program else {
        return Err(Box::new(EnvironmentError::NoProgram {
            src: file.named_source(),
            span: SourceSpan::new(0.into(), 0),
        }));
    };
    let spec = specification.map(|id| sources.get(id));
    let spec_text = spec.map_or("", |f| f.text.as_str());
    let bad = |key: &str, span: SourceSpan, why: String| {
        Box::new(EnvironmentError::BadValue {
            key: key.to_string(),
            why,
            src: spec.unwrap_or(file).named_source(),
            span,
            help: None,
        })
    };
    let settings = match name.rsplit('/').next().unwrap_or(&name) {
        "honda81" => Settings::Collision(collision::Settings::read(spec_text, bad)?),
        "chiba" => Settings::Light(light::Settings::read(spec_text, bad)?),
        "clover" => Settings::Clover(clover::Settings::read(spec_text, &files.data, bad)?),
        "density" => Settings::Density(density::Settings::read(spec_text, bad)?),
        _ => {
            return Err(Box::new(EnvironmentError::UnknownProgram {
                name,
                known: PROGRAMS.join(", "),
                src: file.named_source(),
                span,
            }))
        }
    };
    Ok(EnvironmentSpec { settings, fields })
}

/// The first number of `value` (cpfg reads values with `atof`, which
/// stops at the first character that cannot continue a number).
pub(super) fn number(value: &str) -> Option<f64> {
    let v = value.trim_start();
    let end = v
        .char_indices()
        .take_while(|&(i, c)| {
            c.is_ascii_digit()
                || c == '.'
                || ((c == '-' || c == '+')
                    && (i == 0 || matches!(v.as_bytes()[i - 1], b'e' | b'E')))
                || ((c == 'e' || c == 'E') && i > 0)
        })
        .last()
        .map_or(0, |(i, c)| i + c.len_utf8());
    v[..end].parse().ok()
}

/// `on` / `off` (cpfg compares with "on"; anything else is off).
pub(super) fn switch(value: &str) -> bool {
    value.split_whitespace().next() == Some("on")
}
