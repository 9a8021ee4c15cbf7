//! Turtle errors: a derived string the turtle cannot draw. Input: the
//! offending module (its 1-based position in the string and its text);
//! output: a diagnostic that says what to change.

use miette::{Diagnostic, NamedSource, SourceSpan};
use thiserror::Error;

use crate::resolve::ir::{Production, SuccModule};
use crate::resolve::{Program, CLOSE_BRACKET, OPEN_BRACKET};

#[derive(Debug, Error, Diagnostic)]
pub enum TurtleError {
    #[error("module {index} of the string, `{text}`, has the value {value}, which the turtle cannot draw")]
    #[diagnostic(
        code(lsys::turtle::non_finite),
        help("an expression divided by zero or overflowed; check the production that writes `{symbol}`, e.g. with `lsys derive FILE | tr ' ' '\\n' | grep -n nan`")
    )]
    NonFinite {
        index: usize,
        text: String,
        symbol: String,
        value: f64,
    },

    #[error("after module {index} of the string, `{text}`, the turtle's position or width is beyond the range of the model's numbers (about ±3.4e38)")]
    #[diagnostic(
        code(lsys::turtle::overflow),
        help("the steps, angles or scale factors grow without bound; check the production that writes `{symbol}`, or derive fewer steps")
    )]
    Overflow {
        index: usize,
        text: String,
        symbol: String,
    },

    #[error("module {index} of the string, `{text}`, places a component whose size or position is beyond the range of the model's numbers (about ±3.4e38)")]
    #[diagnostic(
        code(lsys::turtle::component_overflow),
        help("the component's scale factors or its scope are too large for the model; check the production that writes `{symbol}`")
    )]
    ComponentOverflow {
        index: usize,
        text: String,
        symbol: String,
    },

    #[error("the model would have more than {limit} triangles: module {index} of the string, `{text}`, is shape {count}, and every shape is at least one triangle")]
    #[diagnostic(
        code(lsys::turtle::too_many_triangles),
        help("derive fewer steps or make fewer shapes, or raise the limit with `--max-triangles N`; shapes are counted as they are made, before any is meshed (docs/limits.md)")
    )]
    TooManyShapes {
        limit: usize,
        count: usize,
        index: usize,
        text: String,
    },

    #[error("the splits and repeats lay out more than {limit} pieces in all; module {index} of the string, `{text}`, is one past it")]
    #[diagnostic(
        code(lsys::turtle::piece_limit),
        help("nested repeats multiply: each lays out its pieces in every piece of the one around it; make the pieces larger or the scopes smaller (docs/limits.md)")
    )]
    PieceLimit {
        limit: usize,
        index: usize,
        text: String,
    },

    #[error("module {index} of the string is a `]` with no `[` before it{written}")]
    #[diagnostic(code(lsys::turtle::unbalanced_bracket))]
    UnbalancedBracket {
        index: usize,
        /// Which step first wrote a stray `]`, when the caller could find
        /// out (printed as ", first written by derivation step 3").
        written: WrittenAt,
        /// The grammar, when a production is found to blame.
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("this writes a `]` it does not open")]
        written_by: Option<SourceSpan>,
        #[help]
        help: String,
    },

    #[error("module {index} of the string is a `}}` with no `{{` before it")]
    #[diagnostic(
        code(lsys::turtle::unbalanced_polygon),
        help("every `}}` must close a polygon opened by `{{`")
    )]
    UnopenedPolygon { index: usize },

    #[error("{} opened with `{{` never closed by `}}`", if *count == 1 { "a polygon is".to_string() } else { format!("{count} polygons are") })]
    #[diagnostic(
        code(lsys::turtle::unclosed_polygon),
        help("close every polygon with `}}`; the first one was opened by module {first}")
    )]
    UnclosedPolygon { count: usize, first: usize },

    #[error("module {index} of the string, `{text}`, divides the step scale by zero")]
    #[diagnostic(code(lsys::turtle::zero_scale), help("`@Dd(s)` needs s ≠ 0"))]
    ZeroScale { index: usize, text: String },

    /// A split that cannot be laid out, and the other shape-command
    /// errors (boxed: their spans would make every turtle error large).
    #[error(transparent)]
    #[diagnostic(transparent)]
    Shape(Box<ShapeError>),
}

/// Errors of the shape commands (docs/shapes.md).
#[derive(Debug, Error, Diagnostic)]
pub enum ShapeError {
    #[error("module {index} of the string, `{text}`, cannot split its scope: {problem}")]
    #[diagnostic(code(lsys::turtle::split_misfit))]
    SplitMisfit {
        index: usize,
        text: String,
        problem: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("{asked} in a scope {scope} long")]
        written_by: Option<SourceSpan>,
        asked: String,
        scope: String,
        #[help]
        help: String,
    },

    #[error("module {index} of the string, `{text}`, needs {wanted} after it, but {found}")]
    #[diagnostic(code(lsys::turtle::split_branches))]
    SplitBranches {
        index: usize,
        text: String,
        wanted: String,
        found: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("this split")]
        written_by: Option<SourceSpan>,
        #[help]
        help: String,
    },

    #[error("module {index} of the string, `{text}`, cannot build its roof: {problem}")]
    #[diagnostic(code(lsys::turtle::bad_roof))]
    BadRoof {
        index: usize,
        text: String,
        problem: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("this roof")]
        written_by: Option<SourceSpan>,
        #[help]
        help: String,
    },

    #[error("module {index} of the string, `{text}`, names texture {texture}, which no `texture {texture}:` header gives")]
    #[diagnostic(code(lsys::turtle::no_texture))]
    NoTexture {
        index: usize,
        text: String,
        texture: usize,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("used here")]
        written_by: Option<SourceSpan>,
        #[help]
        help: String,
    },

    #[error("module {index} of the string, `{text}`, needs a scope, and none is set")]
    #[diagnostic(code(lsys::turtle::no_scope))]
    NoScope {
        index: usize,
        text: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("used here")]
        written_by: Option<SourceSpan>,
        #[help]
        help: String,
    },
}

impl From<ShapeError> for TurtleError {
    fn from(e: ShapeError) -> TurtleError {
        TurtleError::Shape(Box::new(e))
    }
}

/// The grammar text and the first successor module (axiom first) that
/// writes `sym`: the derivation does not record which production wrote a
/// module, so this is the best place to point at.
pub(crate) fn source_of_symbol(
    program: &Program,
    sym: crate::resolve::ir::SymId,
) -> (NamedSource<crate::source::SourceText>, Option<SourceSpan>) {
    let found = program.axiom.iter().find(|m| m.sym == sym).or_else(|| {
        program
            .productions
            .iter()
            .chain(&program.decomposition)
            .chain(&program.homomorphism)
            .flat_map(|p| p.succ.iter())
            .find(|m| m.sym == sym)
    });
    match found {
        Some(m) => (program.sources.named_source(m.span), Some(m.span.into())),
        None => (
            NamedSource::new("", crate::source::SourceText::from(String::new())),
            None,
        ),
    }
}

/// Where a stray `]` first appeared: the turtle reads only the final
/// string, so the caller that ran the derivation says which step wrote it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BracketOrigin {
    /// The axiom has it (step 0).
    Axiom,
    /// The string after this derivation step is the first that has it.
    Step(u32),
    /// Every derived string is balanced: the homomorphism, applied to the
    /// string of this step, wrote it.
    Homomorphism(u32),
}

/// The end of the stray-`]` message: where it came from, if known (a
/// small value rather than a string, so the error stays small).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WrittenAt(Option<BracketOrigin>);

impl std::fmt::Display for WrittenAt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            None => Ok(()),
            Some(BracketOrigin::Axiom) => write!(f, ", and the axiom already has it"),
            Some(BracketOrigin::Step(n)) => write!(f, ", first written by derivation step {n}"),
            Some(BracketOrigin::Homomorphism(n)) => write!(
                f,
                ", written by the homomorphism applied to the string of step {n}"
            ),
        }
    }
}

/// The first `]` of `modules` (a successor or the axiom) that closes a
/// branch it did not open.
fn first_stray_close(modules: &[SuccModule]) -> Option<&SuccModule> {
    let mut depth = 0i32;
    modules.iter().find(|m| {
        match m.sym {
            OPEN_BRACKET => depth += 1,
            CLOSE_BRACKET => depth -= 1,
            _ => {}
        }
        depth < 0
    })
}

impl TurtleError {
    /// A `]` with no `[` at module `index`. The derivation does not record
    /// which production wrote which module, so the production blamed is
    /// the first whose successor (main, decomposition or homomorphism)
    /// closes more branches than it opens: `check` warned about it.
    pub(crate) fn unbalanced(index: usize, program: &Program) -> TurtleError {
        let all = program
            .productions
            .iter()
            .chain(&program.decomposition)
            .chain(&program.homomorphism);
        TurtleError::blame_stray_close(index, program, all, WrittenAt::default())
    }

    /// This error with the step that first wrote a stray `]`, the
    /// production blamed taken from that step's tables only (main and
    /// decomposition for a derivation step, the homomorphism for the
    /// homomorphism). Other errors are returned unchanged.
    pub fn with_bracket_origin(self, origin: BracketOrigin, program: &Program) -> TurtleError {
        let TurtleError::UnbalancedBracket { index, .. } = self else {
            return self;
        };
        let written = WrittenAt(Some(origin));
        match origin {
            BracketOrigin::Axiom => {
                match first_stray_close(&program.axiom) {
                    Some(m) => TurtleError::UnbalancedBracket {
                        index,
                        written,
                        src: program.sources.named_source(m.span),
                        written_by: Some(m.span.into()),
                        help: "every `]` must close a `[`: add the `[` that the axiom's `]` should close, or remove the `]`".to_string(),
                    },
                    // The axiom is balanced: its decomposition wrote it.
                    None => TurtleError::blame_stray_close(index, program, program.decomposition.iter(), written),
                }
            }
            BracketOrigin::Step(_) => {
                let prods = program.productions.iter().chain(&program.decomposition);
                TurtleError::blame_stray_close(index, program, prods, written)
            }
            BracketOrigin::Homomorphism(_) => {
                TurtleError::blame_stray_close(index, program, program.homomorphism.iter(), written)
            }
        }
    }

    fn blame_stray_close<'a>(
        index: usize,
        program: &Program,
        mut candidates: impl Iterator<Item = &'a Production>,
        written: WrittenAt,
    ) -> TurtleError {
        let general = "every `]` must close a `[`; the productions that write brackets must write them in pairs";
        match candidates.find(|p| first_stray_close(&p.succ).is_some()) {
            Some(p) => TurtleError::UnbalancedBracket {
                index,
                written,
                src: program.sources.named_source(p.span),
                written_by: Some(p.span.into()),
                help: format!(
                    "{general}: add the `[` that this production's `]` should close, or remove the `]`"
                ),
            },
            None => TurtleError::UnbalancedBracket {
                index,
                written,
                src: NamedSource::new("", crate::source::SourceText::from(String::new())),
                written_by: None,
                help: general.to_string(),
            },
        }
    }
}
