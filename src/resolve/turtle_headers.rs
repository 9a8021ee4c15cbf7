//! Turtle headers: `angle:`, `step:`, `width:`, `dialect:`, `colour i:` and
//! `texture i:` (textures.rs) statements -> [`TurtleSettings`]. Each is a constant; each may appear
//! once (a colour once per index).

use super::error::ResolveError;
use super::expr::Scope;
use super::ir::TurtleSettings;
use super::Resolver;
use crate::lang::Dialect;
use crate::parse::ast::{self, HeaderKind};
use crate::source::Span;

/// The settings gathered so far and where each was first given.
#[derive(Default)]
pub(super) struct TurtleHeaders {
    pub settings: TurtleSettings,
    angle: Option<Span>,
    step: Option<Span>,
    width: Option<Span>,
    dialect: Option<Span>,
    colours: Vec<(usize, Span)>,
    textures: Vec<(usize, Span)>,
}

impl TurtleHeaders {
    /// Where texture `i` was first given, if it was.
    pub(super) fn texture_first(&self, i: usize) -> Option<Span> {
        self.textures.iter().find(|(j, _)| *j == i).map(|&(_, s)| s)
    }

    pub(super) fn add_texture(&mut self, at: Span, t: super::ir::Texture) {
        self.textures.push((t.index, at));
        self.settings.textures.push(t);
    }
}

impl Resolver {
    /// Handles `h` if it is a turtle header; returns false otherwise.
    pub(super) fn turtle_header(
        &mut self,
        h: &ast::Header,
        scope: &Scope,
        t: &mut TurtleHeaders,
    ) -> bool {
        match &h.kind {
            HeaderKind::Angle(e) => {
                if self.once(
                    h,
                    "angle:",
                    &mut t.angle,
                    "keep one `angle:`; to change it for one run use `--angle DEGREES`",
                ) {
                    t.settings.angle = self.const_real(e, scope, "angle", -3600.0..=3600.0);
                }
            }
            HeaderKind::Step(e) => {
                if self.once(h, "step:", &mut t.step, "keep one `step:`") {
                    t.settings.step = self.const_real(e, scope, "step", 0.0..=1e9);
                }
            }
            HeaderKind::Width(e) => {
                if self.once(
                    h,
                    "width:",
                    &mut t.width,
                    "keep one `width:`; to change it for one run use `--width W`",
                ) {
                    t.settings.width = self.const_real(e, scope, "width", 0.0..=1e9);
                }
            }
            HeaderKind::Dialect(name, span) => {
                if self.once(h, "dialect:", &mut t.dialect, "a file has one dialect") {
                    match Dialect::from_name(name) {
                        // The loader decided the profile from this header.
                        Some(_) => {}
                        None => self.error(ResolveError::BadValue {
                            what: "dialect".to_string(),
                            why: format!("`{name}` is not a dialect"),
                            src: self.sources.named_source(*span),
                            span: (*span).into(),
                            help: Some("write `dialect: paper` (the Pailou paper's Table 1: `%` rolls 180°, `$` pitches 180°) or `dialect: cpfg` (`%` cuts the branch, `$` ends a sub-L-system)".to_string()),
                        }),
                    }
                }
            }
            HeaderKind::Colour(index, hex, _) => {
                let Some(i) = self.const_count(index, scope, "colour index", 255) else {
                    return true;
                };
                let i = i as usize;
                if let Some(&(_, first)) = t.colours.iter().find(|(j, _)| *j == i) {
                    self.duplicate(
                        h,
                        &format!("colour {i}:"),
                        first,
                        "each colour index is set once",
                    );
                    return true;
                }
                t.colours.push((i, h.keyword));
                t.settings.palette.push((i, parse_hex(hex)));
            }
            HeaderKind::Texture(index, file, span) => {
                self.texture_header(h, index, file, *span, scope, t);
            }
            _ => return false,
        }
        true
    }

    /// Records the first `what` header; reports a second one.
    fn once(&mut self, h: &ast::Header, what: &str, first: &mut Option<Span>, help: &str) -> bool {
        if let Some(f) = *first {
            self.duplicate(h, what, f, help);
            false
        } else {
            *first = Some(h.keyword);
            true
        }
    }

    fn const_real(
        &mut self,
        e: &ast::Expr,
        scope: &Scope,
        what: &str,
        range: std::ops::RangeInclusive<f64>,
    ) -> Option<f64> {
        let x = self.const_num(e, scope, what)?;
        if !range.contains(&x) {
            self.error(ResolveError::BadValue {
                what: what.to_string(),
                why: format!("{x} is not from {} to {}", range.start(), range.end()),
                src: self.sources.named_source(e.span),
                span: e.span.into(),
                help: None,
            });
            return None;
        }
        Some(x)
    }
}

/// `#rrggbb` (checked by the grammar) -> sRGB channels in 0..=1.
fn parse_hex(hex: &str) -> [f32; 3] {
    let channel = |k: usize| {
        u8::from_str_radix(&hex[1 + 2 * k..3 + 2 * k], 16).map_or(0.0, |v| v as f32 / 255.0)
    };
    [channel(0), channel(1), channel(2)]
}
