//! Diagnostics rendering: any stage's errors -> text. The CLI renders with
//! colour for a terminal; tests and pipes get the colour-free form at a
//! fixed width, so snapshots are stable.

use miette::{Diagnostic, GraphicalReportHandler, GraphicalTheme, Severity};

/// Width of rendered diagnostics in snapshots and pipes.
pub const WIDTH: usize = 100;

/// Renders one diagnostic without colour at [`WIDTH`] columns.
pub fn render_plain(d: &dyn Diagnostic) -> String {
    render(d, false)
}

/// Renders one diagnostic, with ANSI colour when `color` is set.
pub fn render(d: &dyn Diagnostic, color: bool) -> String {
    let theme = if color {
        GraphicalTheme::unicode()
    } else {
        GraphicalTheme::unicode_nocolor()
    };
    let handler = GraphicalReportHandler::new_themed(theme)
        .with_width(WIDTH)
        .with_links(false);
    let mut out = String::new();
    if handler.render_report(&mut out, d).is_err() {
        out = format!("{d}\n");
    }
    out
}

/// Whether a diagnostic is an error (as opposed to a warning or advice).
pub fn is_error(d: &dyn Diagnostic) -> bool {
    matches!(d.severity(), None | Some(Severity::Error))
}
