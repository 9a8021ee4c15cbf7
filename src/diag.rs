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

/// Every diagnostic of a failed compilation or run, errors first as they
/// were found, then warnings. It is itself an error and a miette
/// [`Diagnostic`] (the first error, with the others as related
/// diagnostics), so a test, the CLI or an editor renders it the same way.
#[derive(Debug)]
pub struct Diagnostics {
    reports: Vec<miette::Report>,
    /// The root input could not be read at all (the CLI's exit code 66).
    input: bool,
    /// The files on disk the failed compilation read (`watch` watches them).
    files: Vec<std::path::PathBuf>,
}

impl Diagnostics {
    /// Diagnostics of a grammar (all errors and warnings).
    pub fn new(reports: Vec<miette::Report>) -> Diagnostics {
        Diagnostics {
            reports,
            input: false,
            files: Vec::new(),
        }
    }

    /// The same, naming the files on disk the compilation read.
    pub fn with_files(mut self, files: Vec<std::path::PathBuf>) -> Diagnostics {
        self.files = files;
        self
    }

    /// The files on disk the failed compilation had read (root, includes,
    /// cpfg side files), so that a watcher can wait for a fix in any.
    pub fn files(&self) -> &[std::path::PathBuf] {
        &self.files
    }

    /// One diagnostic.
    pub fn one(d: impl Diagnostic + Send + Sync + 'static) -> Diagnostics {
        Diagnostics::new(vec![miette::Report::new(d)])
    }

    /// The root input could not be read (`d` says why).
    pub fn input(d: impl Diagnostic + Send + Sync + 'static) -> Diagnostics {
        Diagnostics {
            input: true,
            ..Diagnostics::one(d)
        }
    }

    /// Whether the root input could not be read at all (no file, not a
    /// grammar), as opposed to a grammar with mistakes.
    pub fn is_input_error(&self) -> bool {
        self.input
    }

    /// Every diagnostic, errors and warnings, in order.
    pub fn iter(&self) -> impl Iterator<Item = &(dyn Diagnostic + Send + Sync + 'static)> {
        self.reports.iter().map(|r| r.as_ref())
    }

    /// How many are errors (not warnings).
    pub fn error_count(&self) -> usize {
        self.iter().filter(|d| is_error(*d)).count()
    }

    /// Every diagnostic rendered without colour at [`WIDTH`] columns, one
    /// after the other (snapshot tests).
    pub fn render_plain(&self) -> String {
        self.iter().map(|d| render_plain(d)).collect()
    }

    /// Every diagnostic rendered, with colour when `color` is set.
    pub fn render(&self, color: bool) -> String {
        self.iter().map(|d| render(d, color)).collect()
    }

    /// Which diagnostic stands for all: the first error, else the first.
    fn first_index(&self) -> Option<usize> {
        self.iter()
            .position(|d| is_error(d))
            .or((!self.reports.is_empty()).then_some(0))
    }

    fn first(&self) -> Option<&(dyn Diagnostic + Send + Sync + 'static)> {
        self.first_index().map(|i| self.reports[i].as_ref())
    }
}

impl std::fmt::Display for Diagnostics {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.first() {
            Some(d) => {
                write!(f, "{d}")?;
                let more = self.error_count().saturating_sub(1);
                if more > 0 {
                    write!(
                        f,
                        " (and {more} more error{})",
                        if more == 1 { "" } else { "s" }
                    )?;
                }
                Ok(())
            }
            None => write!(f, "no diagnostics"),
        }
    }
}

impl std::error::Error for Diagnostics {}

impl Diagnostic for Diagnostics {
    fn code<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.first()?.code()
    }
    fn severity(&self) -> Option<Severity> {
        self.first()?.severity()
    }
    fn help<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.first()?.help()
    }
    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        self.first()?.source_code()
    }
    fn labels(&self) -> Option<Box<dyn Iterator<Item = miette::LabeledSpan> + '_>> {
        self.first()?.labels()
    }
    fn related<'a>(&'a self) -> Option<Box<dyn Iterator<Item = &'a dyn Diagnostic> + 'a>> {
        let first = self.first_index();
        Some(Box::new(
            self.iter()
                .enumerate()
                .filter(move |(i, _)| Some(*i) != first)
                .map(|(_, d)| d as &dyn Diagnostic),
        ))
    }
}
