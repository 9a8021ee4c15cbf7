//! Resolve errors and warnings (`lsys::resolve::*`): names, arities,
//! defines and everything else that is wrong with a grammar that
//! parsed.

use miette::{Diagnostic, NamedSource, SourceSpan};
use thiserror::Error;

type Src = NamedSource<crate::source::SourceText>;

#[derive(Debug, Error, Diagnostic)]
pub enum ResolveError {
    #[error("`{name}` is defined twice")]
    #[diagnostic(
        code(lsys::resolve::duplicate_define),
        help("remove one of the definitions, or give the second a different name; to change a value for one run, give it as an option (`-D {name}=VALUE`)")
    )]
    DuplicateDefine {
        name: String,
        #[source_code]
        src: Src,
        #[label("defined again here")]
        span: SourceSpan,
        #[label("first defined here")]
        first: Option<SourceSpan>,
    },

    /// A define given as an option (`-D NAME=VALUE` on the command line,
    /// `:set` in the REPL, `GrammarOptions::define` in the library) that
    /// names no `#define` of the grammar.
    #[error("the define `{name}` given as an option matches no #define in {file}")]
    #[diagnostic(code(lsys::resolve::unknown_override))]
    UnknownOverride {
        name: String,
        /// The grammar's (root) file name.
        file: String,
        #[help]
        help: String,
    },

    #[error("bad value for the define `{name}` given as an option: {why}")]
    #[diagnostic(code(lsys::resolve::bad_override))]
    BadOverride {
        name: String,
        why: String,
        #[help]
        help: Option<String>,
    },

    #[error("unknown name `{name}`")]
    #[diagnostic(code(lsys::resolve::unknown_name))]
    UnknownName {
        name: String,
        #[source_code]
        src: Src,
        #[label("not a parameter, #define or function")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("{what}, probably from the include that failed")]
    #[diagnostic(code(lsys::resolve::from_failed_include))]
    FromFailedInclude {
        what: String,
        #[source_code]
        src: Src,
        #[label(collection, "first use")]
        uses: Vec<miette::LabeledSpan>,
        #[label("this include failed")]
        include: Option<SourceSpan>,
        #[help]
        help: String,
    },

    #[error("{what} closes a branch it did not open: a `]` with no `[` before it")]
    #[diagnostic(code(lsys::resolve::unmatched_bracket))]
    StrayClose {
        what: String,
        #[source_code]
        src: Src,
        #[label(collection)]
        spans: Vec<miette::LabeledSpan>,
        #[help]
        help: String,
    },

    /// [`ResolveError::StrayClose`] in a successor: a warning, as a cpfg
    /// model may close there a branch another production opened.
    #[error("{what} closes a branch it did not open: a `]` with no `[` before it")]
    #[diagnostic(code(lsys::resolve::unmatched_bracket), severity(Warning))]
    StrayCloseWarning {
        what: String,
        #[source_code]
        src: Src,
        #[label(collection)]
        spans: Vec<miette::LabeledSpan>,
        #[help]
        help: String,
    },

    #[error("{what} opens a branch with `[` and never closes it")]
    #[diagnostic(code(lsys::resolve::unclosed_bracket), severity(Warning))]
    UnclosedBracket {
        what: String,
        #[source_code]
        src: Src,
        #[label(collection)]
        spans: Vec<miette::LabeledSpan>,
        #[help]
        help: String,
    },

    #[error("`$` pitches the turtle 180° here (the paper's dialect); in ABOP and cpfg it rolls the turtle level")]
    #[diagnostic(
        code(lsys::resolve::dialect_hint),
        severity(Advice),
        help("this file reads like an ABOP/cpfg model but is read in the paper's dialect, the default for `.lsys` files; if `$` should roll the turtle so its left axis is horizontal, add the header `dialect: cpfg`; add `dialect: paper` to keep the paper's meaning and silence this hint")
    )]
    DollarDialect {
        #[source_code]
        src: Src,
        #[label("`$` is pitch 180° in the paper's dialect")]
        span: SourceSpan,
    },

    #[error("`%` rolls the turtle 180° here (the paper's dialect); in ABOP and cpfg it cuts the rest of the branch")]
    #[diagnostic(
        code(lsys::resolve::dialect_hint),
        severity(Advice),
        help("this file reads like an ABOP/cpfg model but is read in the paper's dialect, the default for `.lsys` files; if `%` should cut the branch (shedding, pruning), add the header `dialect: cpfg`; add `dialect: paper` to keep the paper's meaning and silence this hint")
    )]
    PercentDialect {
        #[source_code]
        src: Src,
        #[label("`%` is roll 180° in the paper's dialect")]
        span: SourceSpan,
    },

    #[error("unknown component `~{name}`")]
    #[diagnostic(code(lsys::resolve::unknown_component))]
    UnknownComponent {
        name: String,
        #[source_code]
        src: Src,
        #[label("not a declared component")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("unknown function `{name}`")]
    #[diagnostic(code(lsys::resolve::unknown_function))]
    UnknownFunction {
        name: String,
        #[source_code]
        src: Src,
        #[label("no built-in function or function-like #define has this name")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("`{name}` takes {expected} argument{}, found {found}", if *expected == 1 { "" } else { "s" })]
    #[diagnostic(code(lsys::resolve::call_arity))]
    CallArity {
        name: String,
        expected: usize,
        found: usize,
        #[source_code]
        src: Src,
        #[label("called here")]
        span: SourceSpan,
        #[help]
        help: Option<String>,
    },

    #[error("table `{name}` has {found} values for {expected} elements {dims}")]
    #[diagnostic(code(lsys::resolve::table_size))]
    TableSize {
        name: String,
        found: usize,
        expected: usize,
        dims: String,
        #[source_code]
        src: Src,
        #[label("{found} values")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("{what}")]
    #[diagnostic(code(lsys::resolve::not_a_table))]
    NotATable {
        what: String,
        #[source_code]
        src: Src,
        #[label("indexed here")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("`{name}` is a table {dims}; {problem}")]
    #[diagnostic(code(lsys::resolve::table_use))]
    TableUse {
        name: String,
        dims: String,
        problem: String,
        #[source_code]
        src: Src,
        #[label("here")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("index {value} of `{name}` is outside {lo}..{hi}")]
    #[diagnostic(
        code(lsys::resolve::table_index),
        help("table indices are whole numbers within the ranges of the table's #define {dims}")
    )]
    TableIndex {
        name: String,
        value: f64,
        lo: i64,
        hi: i64,
        dims: String,
        #[source_code]
        src: Src,
        #[label("this index")]
        span: SourceSpan,
    },

    #[error("`{name}` has no value")]
    #[diagnostic(code(lsys::resolve::define_without_value))]
    DefineWithoutValue {
        name: String,
        #[source_code]
        src: Src,
        #[label("used here")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("`{name}` is defined in terms of itself: {chain}")]
    #[diagnostic(
        code(lsys::resolve::define_cycle),
        help("a #define may use other defines, but not itself, directly or through others")
    )]
    DefineCycle {
        name: String,
        chain: String,
        #[source_code]
        src: Src,
        #[label("used here")]
        span: SourceSpan,
    },

    #[error("`{name}` is used before its #define")]
    #[diagnostic(code(lsys::resolve::define_after_use))]
    DefineAfterUse {
        name: String,
        #[source_code]
        src: Src,
        #[label("used here")]
        span: SourceSpan,
        #[label("defined later, here")]
        def: Option<SourceSpan>,
        #[help]
        help: String,
    },

    #[error("unknown module `{name}`")]
    #[diagnostic(code(lsys::resolve::unknown_module))]
    UnknownModule {
        name: String,
        #[source_code]
        src: Src,
        #[label("no production, declaration, component or turtle command has this name")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("`{name}` takes {expected}, found {found}")]
    #[diagnostic(code(lsys::resolve::arity))]
    Arity {
        name: String,
        expected: String,
        found: String,
        #[source_code]
        src: Src,
        #[label("{found} here")]
        span: SourceSpan,
        #[label("its parameters are declared here")]
        decl: Option<SourceSpan>,
        #[help]
        help: String,
    },

    #[error("the parameters of a predecessor must be names")]
    #[diagnostic(
        code(lsys::resolve::pattern_param),
        help("write a name for each parameter (`A(x,y)`) and test values in the condition: `A(x,y) : x == 1 --> ...`")
    )]
    PatternParam {
        #[source_code]
        src: Src,
        #[label("this is not a plain name")]
        span: SourceSpan,
    },

    #[error("parameter `{name}` is bound twice in one production")]
    #[diagnostic(
        code(lsys::resolve::duplicate_parameter),
        help("give each parameter of the predecessor and its contexts its own name")
    )]
    DuplicateParam {
        name: String,
        #[source_code]
        src: Src,
        #[label("bound again here")]
        span: SourceSpan,
        #[label("first bound here")]
        first: SourceSpan,
    },

    #[error("`else` has no earlier production for `{pred}` to be the alternative of")]
    #[diagnostic(
        code(lsys::resolve::else_first),
        help("`else` applies when no earlier production with the same predecessor matched; put the conditional productions for `{pred}` above this one, or drop the `else`")
    )]
    ElseFirst {
        pred: String,
        #[source_code]
        src: Src,
        #[label("first production for `{pred}`")]
        span: SourceSpan,
    },

    #[error("`{name}` is a cpfg turtle command lsys does not draw; it is kept as a module that draws nothing")]
    #[diagnostic(
        code(lsys::resolve::ignored_command),
        severity(Warning),
        help("see `lsys commands` for the commands the turtle draws")
    )]
    IgnoredCommand {
        name: String,
        #[source_code]
        src: Src,
        #[label("not drawn")]
        span: SourceSpan,
    },

    #[error("`?E` modules are answered by an environmental program, which lsys does not run")]
    #[diagnostic(
        code(lsys::resolve::environment),
        severity(Warning),
        help("cpfg runs this model with `-e PROGRAM` (see its `specifications`); here `?E` keeps the parameters the grammar writes, so the parts of the model that respond to the environment derive differently")
    )]
    Environment {
        #[source_code]
        src: Src,
        #[label("first `?E` here")]
        span: SourceSpan,
    },

    #[error("the parameter `{name}` hides `#define {name}` inside this production")]
    #[diagnostic(
        code(lsys::resolve::param_hides_define),
        severity(Warning),
        help("inside the production `{name}` is the parameter; to use the define there, name the parameter otherwise (e.g. `{name}1`)")
    )]
    ParamHidesDefine {
        name: String,
        #[source_code]
        src: Src,
        #[label("this parameter")]
        span: SourceSpan,
        #[label("hides this define")]
        define: Option<SourceSpan>,
    },

    #[error("`{name}` is a #define, but here it is read as the modules {modules}")]
    #[diagnostic(
        code(lsys::resolve::define_as_module),
        severity(Warning),
        help("a define gives a value, not modules: use it as a parameter (`F({name})`) or in an expression; to mean a module, rename the define")
    )]
    DefineAsModule {
        name: String,
        modules: String,
        #[source_code]
        src: Src,
        #[label("read as {modules}")]
        span: SourceSpan,
        #[label("the define")]
        define: Option<SourceSpan>,
    },

    #[error(
        "every production is in the homomorphism, so the {steps} derivation steps rewrite nothing"
    )]
    #[diagnostic(
        code(lsys::resolve::only_homomorphism),
        severity(Warning),
        help("the homomorphism only changes what the turtle draws; productions that grow the string go before the `homomorphism` line")
    )]
    OnlyHomomorphism {
        steps: u32,
        #[source_code]
        src: Src,
        #[label("the first production, after `homomorphism`")]
        span: SourceSpan,
    },

    #[error("this condition reads no parameter and is always false: the production never fires")]
    #[diagnostic(
        code(lsys::resolve::constant_condition),
        severity(Warning),
        help("it depends only on #defines and numbers; compare a parameter of the predecessor (e.g. `x < N`), or change the define (`-D NAME=VALUE`)")
    )]
    ConstantCondition {
        #[source_code]
        src: Src,
        #[label("always false")]
        span: SourceSpan,
    },

    #[error("colour index {index} is {what}")]
    #[diagnostic(code(lsys::resolve::colour_index), severity(Warning))]
    ColourIndex {
        index: f64,
        what: String,
        #[source_code]
        src: Src,
        #[label("this colour")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("this production can never fire: {why}")]
    #[diagnostic(code(lsys::resolve::never_fires), severity(Warning))]
    NeverFires {
        why: String,
        #[source_code]
        src: Src,
        #[label("never in the strings")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("this production can never apply")]
    #[diagnostic(code(lsys::resolve::unreachable), severity(Warning))]
    Unreachable {
        #[source_code]
        src: Src,
        #[label("never reached")]
        span: SourceSpan,
        #[label("this earlier production always applies to `{pred}` first")]
        earlier: Option<SourceSpan>,
        pred: String,
        #[help]
        help: String,
    },

    #[error("{what} must be a constant")]
    #[diagnostic(code(lsys::resolve::not_constant))]
    NotConstant {
        what: String,
        #[source_code]
        src: Src,
        #[label("this depends on parameters or random numbers")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("bad {what}: {why}")]
    #[diagnostic(code(lsys::resolve::bad_value))]
    BadValue {
        what: String,
        why: String,
        #[source_code]
        src: Src,
        #[label("{why}")]
        span: SourceSpan,
        #[help]
        help: Option<String>,
    },

    #[error("`{what}` appears twice")]
    #[diagnostic(code(lsys::resolve::duplicate_header))]
    DuplicateHeader {
        what: String,
        #[source_code]
        src: Src,
        #[label("again here")]
        span: SourceSpan,
        #[label("first here")]
        first: Option<SourceSpan>,
        #[help]
        help: String,
    },

    #[error("{what} is not supported")]
    #[diagnostic(code(lsys::resolve::unsupported))]
    Unsupported {
        what: String,
        #[source_code]
        src: Src,
        #[label("here")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("{what}")]
    #[diagnostic(code(lsys::resolve::misplaced))]
    Misplaced {
        what: String,
        #[source_code]
        src: Src,
        #[label("here")]
        span: SourceSpan,
        #[help]
        help: String,
    },

    #[error("the grammar has no axiom")]
    #[diagnostic(
        code(lsys::resolve::no_axiom),
        help("add the starting string, e.g. `Axiom: F` (also written `axiom:`, `ω:` or `Ω:`)")
    )]
    NoAxiom {
        #[source_code]
        src: Src,
        #[label("in this file")]
        span: SourceSpan,
    },

    #[error("division by zero in a constant expression")]
    #[diagnostic(
        code(lsys::resolve::division_by_zero),
        help("the divisor is zero for every module; check the #define values it uses")
    )]
    DivisionByZero {
        #[source_code]
        src: Src,
        #[label("this divisor is 0")]
        span: SourceSpan,
    },
}
