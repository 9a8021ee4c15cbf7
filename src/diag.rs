//! Diagnostics rendering: any stage's errors -> text. The CLI renders with
//! colour for a terminal; tests and pipes get the colour-free form at a
//! fixed width, so snapshots are stable. A library caller reads each
//! diagnostic as a plain [`Message`] (code, severity, place, text).

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
    let rendered = match too_wide(d) {
        Some((file, line, column)) => {
            let shown = Unshown {
                inner: d,
                text: format!(
                    "{d}\n  at {}:{line}:{column} (a line too long to show)",
                    file.as_deref().unwrap_or("<input>")
                ),
            };
            handler.render_report(&mut out, &shown)
        }
        None => handler.render_report(&mut out, d),
    };
    if rendered.is_err() {
        out = format!("{d}\n");
    }
    out
}

/// Labels past this column are not drawn under their line: miette's
/// printer pads to the column with a width argument, which panics past
/// 65,535 ("Formatting argument out of range"), and a line that long is
/// unreadable in a terminal anyway.
const MAX_SNIPPET_COLUMN: usize = 10_000;

/// The place of `d` when one of its labels (or a related diagnostic's)
/// ends past [`MAX_SNIPPET_COLUMN`].
fn too_wide(d: &dyn Diagnostic) -> Option<(Option<String>, usize, usize)> {
    let wide = |d: &dyn Diagnostic| -> bool {
        let (Some(src), Some(labels)) = (d.source_code(), d.labels()) else {
            return false;
        };
        labels.into_iter().any(|l| {
            src.read_span(l.inner(), 0, 0)
                .is_ok_and(|c| c.column() + l.len() > MAX_SNIPPET_COLUMN)
        })
    };
    let related = d.related().into_iter().flatten().any(wide);
    if !wide(d) && !related {
        return None;
    }
    Some(place(d).unwrap_or((None, 0, 0)))
}

/// A diagnostic shown without its source lines: its message with the place
/// in words, and its code, severity and help.
struct Unshown<'a> {
    inner: &'a dyn Diagnostic,
    text: String,
}

impl std::fmt::Debug for Unshown<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl std::fmt::Display for Unshown<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl std::error::Error for Unshown<'_> {}

impl Diagnostic for Unshown<'_> {
    fn code<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.inner.code()
    }
    fn severity(&self) -> Option<Severity> {
        self.inner.severity()
    }
    fn help<'a>(&'a self) -> Option<Box<dyn std::fmt::Display + 'a>> {
        self.inner.help()
    }
}

/// Whether a diagnostic is an error (as opposed to a warning or advice).
pub fn is_error(d: &dyn Diagnostic) -> bool {
    matches!(d.severity(), None | Some(Severity::Error))
}

/// How grave a [`Message`] is. (miette's `Severity` is its counterpart
/// inside the crate; this one is lsys's own, so that a caller needs no
/// miette to match on it.)
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Level {
    /// The grammar did not compile, or the run stopped.
    Error,
    /// Worth a look; the grammar still compiled.
    Warning,
    /// A hint.
    Advice,
}

impl Level {
    /// `error`, `warning` or `advice`, as the short form writes it.
    pub fn as_str(self) -> &'static str {
        match self {
            Level::Error => "error",
            Level::Warning => "warning",
            Level::Advice => "advice",
        }
    }
}

impl std::fmt::Display for Level {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One diagnostic as plain data: what a caller of the library reads from
/// [`Diagnostics::messages`] (a test, an editor, a web page). Named
/// `Message`, not `Diagnostic`, so that it does not clash with miette's
/// `Diagnostic` trait in code that uses both.
///
/// The place is where the diagnostic's primary label points (its first
/// label when none is marked primary): `file`, `line` and `column` are all
/// `Some` or all `None` (a diagnostic about no place in a file, such as a
/// define given as an option that matches nothing). Lines and columns
/// count from 1; a column counts bytes from the start of the line, as the
/// rendered text's `file:line:column` does.
///
/// `Display` is the short, one-line form:
/// `koch.lsys:3:7: error[lsys::resolve::unknown_name]: unknown name `x``.
///
/// ```
/// let err = lsys::Grammar::from_str("koch.lsys", "axiom: F(x)\n").unwrap_err();
/// let m = err.messages().next().unwrap();
/// assert_eq!(m.code.as_deref(), Some("lsys::resolve::unknown_name"));
/// assert_eq!(m.severity, lsys::Level::Error);
/// assert_eq!((m.file.as_deref(), m.line, m.column), (Some("koch.lsys"), Some(1), Some(10)));
/// assert_eq!(m.message, "unknown name `x`");
/// assert!(m.rendered().contains("╭─[koch.lsys:1:10]"));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Message {
    /// The diagnostic's code, e.g. `lsys::resolve::unknown_name` (every
    /// diagnostic of lsys has one; `None` only for one that came from
    /// elsewhere without).
    pub code: Option<String>,
    /// Error, warning or advice.
    pub severity: Level,
    /// The name of the file (or the name given to `Grammar::from_str`)
    /// the diagnostic points into.
    pub file: Option<String>,
    /// The line it points at, from 1.
    pub line: Option<usize>,
    /// The column it points at, from 1 (in bytes).
    pub column: Option<usize>,
    /// The message, one sentence without the place.
    pub message: String,
    /// The help sentence, when the diagnostic has one.
    pub help: Option<String>,
    rendered: String,
}

impl Message {
    /// The typed form of any miette diagnostic.
    pub fn from_diagnostic(d: &dyn Diagnostic) -> Message {
        Message {
            rendered: render_plain(d),
            ..Message::unrendered(d)
        }
    }

    /// The same without the rendering (for the short form).
    fn unrendered(d: &dyn Diagnostic) -> Message {
        let (file, line, column) = match place(d) {
            Some((file, line, column)) => (file, Some(line), Some(column)),
            None => (None, None, None),
        };
        Message {
            code: d.code().map(|c| c.to_string()),
            severity: Message::level_of(d),
            file,
            line,
            column,
            message: d.to_string(),
            help: d.help().map(|h| h.to_string()),
            rendered: String::new(),
        }
    }

    fn level_of(d: &dyn Diagnostic) -> Level {
        match d.severity() {
            Some(Severity::Warning) => Level::Warning,
            Some(Severity::Advice) => Level::Advice,
            None | Some(Severity::Error) => Level::Error,
        }
    }

    /// The diagnostic rendered as the CLI renders it into a pipe: without
    /// colour, at [`WIDTH`] columns, with the source lines it points at.
    pub fn rendered(&self) -> &str {
        &self.rendered
    }

    /// Whether this is an error (not a warning or advice).
    pub fn is_error(&self) -> bool {
        self.severity == Level::Error
    }
}

impl std::fmt::Display for Message {
    /// `file:line:column: severity[code]: message`, each part present
    /// only when the diagnostic has it.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let place = match (&self.file, self.line, self.column) {
            (Some(file), Some(line), Some(column)) => Some((file.as_str(), line, column)),
            _ => None,
        };
        write_short(
            f,
            place,
            self.severity.as_str(),
            self.code.as_deref(),
            &self.message,
        )
    }
}

/// The short form of a diagnostic, `file:line:column: severity[code]:
/// message`, each part written when known: [`Message`]'s `Display`, and
/// the batch index's diagnostics (`driver::batch::ItemDiagnostic`).
pub fn write_short(
    f: &mut std::fmt::Formatter<'_>,
    place: Option<(&str, usize, usize)>,
    severity: &str,
    code: Option<&str>,
    message: &str,
) -> std::fmt::Result {
    if let Some((file, line, column)) = place {
        write!(f, "{file}:{line}:{column}: ")?;
    }
    write!(f, "{severity}")?;
    if let Some(code) = code {
        write!(f, "[{code}]")?;
    }
    write!(f, ": {message}")
}

/// Where a diagnostic points: the file name (when its source has one),
/// line and column from 1, of its primary label (else its first label).
pub fn place(d: &dyn Diagnostic) -> Option<(Option<String>, usize, usize)> {
    let src = d.source_code()?;
    let labels: Vec<miette::LabeledSpan> = d.labels()?.collect();
    let label = labels.iter().find(|l| l.primary()).or(labels.first())?;
    let c = src.read_span(label.inner(), 0, 0).ok()?;
    Some((c.name().map(str::to_string), c.line() + 1, c.column() + 1))
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

    /// One diagnostic already boxed (an exporter's, a guided scene's).
    pub(crate) fn boxed(d: Box<dyn Diagnostic + Send + Sync>) -> Diagnostics {
        Diagnostics::new(vec![miette::Report::new_boxed(d)])
    }

    /// Each of `ds`, in order (warnings handed back beside a result).
    pub(crate) fn all<D: Diagnostic + Send + Sync + 'static>(
        ds: impl IntoIterator<Item = D>,
    ) -> Diagnostics {
        Diagnostics::new(ds.into_iter().map(miette::Report::new).collect())
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

    /// Every diagnostic, errors and warnings, in order, as plain
    /// [`Message`]s (code, severity, place, text, help).
    ///
    /// ```
    /// let err = lsys::Grammar::from_str("g.lsys", "axiom: A(1\n").unwrap_err();
    /// let codes: Vec<String> = err.messages().filter_map(|m| m.code).collect();
    /// assert_eq!(codes, ["lsys::parse::syntax"]);
    /// ```
    pub fn messages(&self) -> impl Iterator<Item = Message> + '_ {
        self.iter().map(|d| Message::from_diagnostic(d))
    }

    /// How many diagnostics, errors and warnings.
    pub fn len(&self) -> usize {
        self.reports.len()
    }

    /// Whether there are none (a grammar's warnings, when it has none).
    pub fn is_empty(&self) -> bool {
        self.reports.is_empty()
    }

    /// Whether any is an error.
    pub fn has_errors(&self) -> bool {
        self.iter().any(|d| is_error(d))
    }

    /// Every diagnostic, errors and warnings, in order, as miette
    /// diagnostics (to render them, or to hand them to miette).
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
    /// The first error (else the first warning) in the short form of
    /// [`Message`], `koch.lsys:3:7: error[lsys::resolve::unknown_name]:
    /// unknown name `x``, then ` (and 2 more errors)` when there are
    /// others of its severity.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Some(d) = self.first() else {
            return write!(f, "no diagnostics");
        };
        let first = Message::unrendered(d);
        write!(f, "{first}")?;
        let more = self
            .iter()
            .filter(|d| Message::level_of(*d) == first.severity)
            .count()
            .saturating_sub(1);
        if more > 0 {
            let s = if more == 1 { "" } else { "s" };
            write!(f, " (and {more} more {}{s})", first.severity)?;
        }
        Ok(())
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
