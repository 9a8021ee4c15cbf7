//! Tests of the preprocessor through its public API. Inputs are small
//! hand-written cpfg-like snippets.

use std::collections::HashMap;
use std::path::PathBuf;

use super::*;

/// Resolves names from a fixed table and records what was asked for.
#[derive(Default)]
struct MapResolver {
    files: HashMap<String, String>,
    asked: Vec<(String, bool)>,
}

impl Resolver for MapResolver {
    fn resolve(
        &mut self,
        _including: &RawFile,
        name: &str,
        angled: bool,
    ) -> Result<RawFile, String> {
        self.asked.push((name.to_string(), angled));
        match self.files.get(name) {
            Some(text) => Ok(raw(name, text)),
            None => Err(format!("no such file: {name}")),
        }
    }
}

fn raw(name: &str, text: &str) -> RawFile {
    RawFile {
        name: name.to_string(),
        key: PathBuf::from(name),
        text: text.to_string(),
    }
}

fn run_with(
    text: &str,
    files: &[(&str, &str)],
    opts: &Options,
) -> (Output, Vec<PreprocessError>, MapResolver) {
    let mut r = MapResolver {
        files: files
            .iter()
            .map(|(n, t)| (n.to_string(), t.to_string()))
            .collect(),
        ..Default::default()
    };
    let (out, errs) = preprocess(raw("root.l", text), &mut r, opts);
    (out, errs, r)
}

/// The root's output; fails on any error or warning.
fn pp(text: &str) -> String {
    let (out, errs, _) = run_with(text, &[], &Options::default());
    assert!(errs.is_empty(), "unexpected errors for {text:?}: {errs:#?}");
    out.files[0].text.clone()
}

/// The single error (or warning) `text` gives, and the original text its span covers.
fn one_error(text: &str) -> (PreprocessError, String) {
    one_error_with(text, &[], &Options::default())
}

fn one_error_with(text: &str, files: &[(&str, &str)], opts: &Options) -> (PreprocessError, String) {
    let (out, errs, _) = run_with(text, files, opts);
    assert_eq!(errs.len(), 1, "expected one error for {text:?}: {errs:#?}");
    let e = errs[0].clone();
    let src = &out.files[e.file].raw.text;
    let covered = src
        .get(e.span.clone())
        .expect("span inside the text")
        .to_string();
    (e, covered)
}

fn lines(s: &str) -> usize {
    s.split('\n').count()
}

#[test]
fn object_macro_expands_and_directive_line_is_blank() {
    assert_eq!(pp("#define N 5\nF(N) +(N)\n"), "\nF(5) +(5)\n");
}

#[test]
fn macro_body_is_arbitrary_turtle_text() {
    let src = "#define LEAF [&F(1)]\n#define BRANCH(a) [+(a)F]\nA --> F LEAF BRANCH(30) @Gc(3)\n";
    assert_eq!(pp(src), "\n\nA --> F [&F(1)] [+(30)F] @Gc(3)\n");
}

#[test]
fn function_macro_with_expressions_and_nested_parens() {
    let src =
        "#define width(x) 0.05*func(1,x)\n#define P(a,b) ?P(a,b)\nF(width(t/(N-1))) P((1,2),y)";
    assert_eq!(pp(src), "\n\nF(0.05*func(1,t/(N-1))) ?P((1,2),y)");
}

#[test]
fn empty_arguments() {
    assert_eq!(
        pp("#define E() e\n#define ONE(a) [a]\nE() ONE()"),
        "\n\ne []"
    );
}

#[test]
fn rescanning_expands_macros_in_results() {
    assert_eq!(pp("#define X Y+Y\n#define Y 7\nX"), "\n\n7+7");
    assert_eq!(
        pp("#define F(a) G(a)\n#define G(b) [b]\n#define V 3\nF(V)"),
        "\n\n\n[3]"
    );
}

#[test]
fn painted_blue_macros_do_not_recurse() {
    assert_eq!(pp("#define A A+1\nA"), "\nA+1");
    assert_eq!(pp("#define P Q\n#define Q P\nP Q"), "\n\nP Q");
    assert_eq!(pp("#define f(x) x+f(x)\nf(1)"), "\n1+f(1)");
}

#[test]
fn function_like_name_without_parenthesis_is_left_alone() {
    assert_eq!(pp("#define G(x) <x>\nG + G(1)"), "\nG + <1>");
}

#[test]
fn stringify_and_paste() {
    assert_eq!(
        pp("#define S(x) #x\nS(F(1)  +  \"q\")"),
        "\n\"F(1) + \\\"q\\\"\""
    );
    assert_eq!(
        pp("#define CAT(a,b) a##b\n#define FG 9\nCAT(F,G) CAT(,x) CAT(y,)"),
        "\n\n9 x y"
    );
    // `#` before something that is not a parameter is cpfg's turtle command.
    assert_eq!(pp("#define W(a) #(a)F\nW(2)"), "\n#(2)F");
}

#[test]
fn variadic_macros() {
    assert_eq!(
        pp("#define V(f, ...) f(__VA_ARGS__)\nV(g, 1, 2) V(h)"),
        "\ng(1, 2) h()"
    );
    assert_eq!(
        pp("#define E(f, ...) f(0, ## __VA_ARGS__)\nE(a) E(b,1)"),
        "\na(0) b(0,1)"
    );
}

#[test]
fn expansions_do_not_glue_into_other_tokens() {
    assert_eq!(pp("#define N -1\n-N F(N)"), "\n- -1 F(-1)");
    assert_eq!(pp("#define R /\nF/R"), "\nF/ /");
}

#[test]
fn hash_in_the_middle_of_a_line_is_text_and_slash_is_a_roll() {
    assert_eq!(
        pp("A --> F #(2) F / F // roll and comment\n  # \n"),
        "A --> F #(2) F / F\n\n"
    );
}

#[test]
fn comments_become_spaces_and_keep_their_newlines() {
    assert_eq!(pp("A/* one\ntwo */B\nC"), "A\n B\nC");
    assert_eq!(pp("#define X 1 /* a\n b */\nX"), "\n\n1");
}

#[test]
fn undef_and_redefine() {
    assert_eq!(
        pp("#define X 1\nX\n#undef X\nX\n#define X 2\nX"),
        "\n1\n\nX\n\n2"
    );
}

#[test]
fn directive_ends_the_search_for_a_parenthesis() {
    assert_eq!(
        pp("#define G(x) <x>\n#define Y 1\nG\n#undef Y\n(Y)"),
        "\n\nG\n\n(Y)"
    );
}

#[test]
fn apostrophe_is_a_turtle_command_not_a_char_literal() {
    assert_eq!(pp("#define C 3\nF';(C)' F"), "\nF';(3)' F");
}

#[test]
fn empty_and_comment_only_files() {
    assert_eq!(pp(""), "");
    assert_eq!(pp("/* a\n b */ // c\n"), "\n\n");
}

#[test]
fn strings_are_not_expanded() {
    assert_eq!(pp("#define X 1\n\"X\" X"), "\n\"X\" 1");
}

#[test]
fn conditionals_nested_and_elif() {
    let src = "#define A 2\n\
               #if A == 1\none\n#elif A == 2\ntwo\n#if 0\nno\n#else\nyes\n#endif\n#else\nthree\n#endif\n\
               #ifdef A\nda\n#endif\n#ifndef A\nnda\n#endif\n#ifndef B\nndb\n#endif";
    let out = pp(src);
    let kept: Vec<&str> = out.lines().filter(|l| !l.is_empty()).collect();
    assert_eq!(kept, ["two", "yes", "da", "ndb"]);
    assert_eq!(lines(&out), lines(src));
}

#[test]
fn elif_after_a_taken_branch_is_not_evaluated() {
    assert_eq!(
        pp("#if 1\na\n#elif 1/0\nb\n#else\nc\n#endif"),
        "\na\n\n\n\n\n"
    );
}

#[test]
fn if_arithmetic() {
    let cases: &[(&str, bool)] = &[
        ("1 + 2 * 3 == 7", true),
        ("(1 + 2) * 3 == 9", true),
        ("10 / 3 == 3 && 10 % 3 == 1", true),
        ("-1 < 0", true),
        ("~0 == -1", true),
        ("!0 && !!5", true),
        ("1 << 4 == 16 && 256 >> 4 == 16", true),
        ("(6 & 3) == 2 && (6 | 3) == 7 && (6 ^ 3) == 5", true),
        ("1 ? 2 : 0", true),
        ("0 ? 1 : 0", false),
        ("0x10 == 16 && 010 == 8 && 5u == 5L", true),
        ("UNKNOWN", false),
        ("UNKNOWN == 0", true),
        ("defined N && defined(N) && !defined M", true),
        ("N * 2 == 8", true),
        ("0 && 1 / 0", false),
        ("1 || 1 / 0", true),
        ("9223372036854775807 + 1 < 0", true),
        ("1 << 70 == 0", true),
    ];
    for (expr, want) in cases {
        let src = format!("#define N 4\n#if {expr}\nyes\n#else\nno\n#endif");
        let out = pp(&src);
        let got = out.contains("yes");
        assert_eq!(got, *want, "#if {expr}: {out:?}");
    }
}

#[test]
fn directives_in_false_branches_are_not_evaluated() {
    let src =
        "#if 0\n#error no\n#include \"missing.l\"\n#if 1/0\n#endif\n#foo\n#define X 1\n#endif\nX";
    let (out, errs, r) = run_with(src, &[], &Options::default());
    assert!(errs.is_empty(), "{errs:#?}");
    assert!(r.asked.is_empty());
    assert!(out.files[0].text.ends_with("\nX"));
    assert_eq!(out.files.len(), 1);
}

#[test]
fn continuation_lines_keep_the_line_count() {
    let src = "#define L [F\\\n+F]\nL\nA \\\nB\nC\n";
    let out = pp(src);
    assert_eq!(out, "\n\n[F+F]\nA B\n\nC\n");
    assert_eq!(lines(&out), lines(src));
    // Blanks after the backslash (GNU cpp accepts them) and CRLF.
    assert_eq!(pp("A \\  \r\nB\r\nC"), "A B\n\nC");
}

#[test]
fn multi_line_invocation_is_expanded_on_its_first_line() {
    let src = "#define M(a,b) a+b\nM(1,\n2) x\ny";
    assert_eq!(pp(src), "\n1+2 x\n\ny");
    // The `(` may be on a later line as well.
    assert_eq!(pp("#define M(a) <a>\nM\n(1)\nz"), "\n<1>\n\nz");
}

#[test]
fn line_and_file_builtins() {
    assert_eq!(pp("\n\n__LINE__ __FILE__"), "\n\n3 \"root.l\"");
}

#[test]
fn command_line_defines_come_first() {
    let opts = Options {
        defines: vec![("LEN".into(), "3".into()), ("SQ(x)".into(), "x*x".into())],
        ..Options::default()
    };
    let (out, errs, _) = run_with("F(LEN) F(SQ(2))\n#ifdef LEN\nyes\n#endif", &[], &opts);
    assert!(errs.is_empty(), "{errs:#?}");
    assert_eq!(out.files[0].text, "F(3) F(2*2)\n\nyes\n");
}

/// Issue 35: `-D` wins over the file's own `#define` (as in `.lsys`
/// files), with no redefinition warning; a `-D` the model neither defines
/// nor mentions is an error naming the nearest macro.
#[test]
fn command_line_defines_win_and_unknown_ones_are_errors() {
    let opts = |d: &[(&str, &str)]| Options {
        defines: d
            .iter()
            .map(|(n, v)| (n.to_string(), v.to_string()))
            .collect(),
        ..Options::default()
    };
    let text = "#define LEN 2\nF(LEN)\n#ifdef DEBUG\nD\n#endif";
    let (out, errs, _) = run_with(text, &[], &opts(&[("LEN", "3")]));
    assert!(errs.is_empty(), "{errs:#?}");
    assert_eq!(out.files[0].text, "\nF(3)\n\n\n");
    // Mentioned only by `#ifdef`: known, and it switches the text on.
    let (out, errs, _) = run_with(text, &[], &opts(&[("DEBUG", "1")]));
    assert!(errs.is_empty(), "{errs:#?}");
    assert!(out.files[0].text.contains('D'));
    let (_, errs, _) = run_with(text, &[], &opts(&[("LNE", "3")]));
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert_eq!(errs[0].kind.code(), "lsys::preprocess::unknown_define");
    assert!(errs[0]
        .help
        .as_deref()
        .unwrap_or("")
        .contains("did you mean `LEN`?"));
}

#[test]
fn include_defines_macros_for_the_includer() {
    let files = [("leaf.l", "#define SIZE 42\nL(SIZE)\n"), ("<std.l>", "")];
    let src = "A\n  #include \"leaf.l\" // the leaf\nF(SIZE)\n#include <std.l>\n";
    let mut r = MapResolver {
        files: files
            .iter()
            .map(|(n, t)| (n.trim_matches(['<', '>']).to_string(), t.to_string()))
            .collect(),
        ..Default::default()
    };
    let (out, errs) = preprocess(raw("root.l", src), &mut r, &Options::default());
    assert!(errs.is_empty(), "{errs:#?}");
    assert_eq!(out.files.len(), 3);
    assert_eq!(
        out.files[0].text,
        "A\n  #include \"leaf.l\"\nF(42)\n#include <std.l>\n"
    );
    assert_eq!(out.files[1].text, "\nL(42)\n");
    assert_eq!(out.files[1].raw.name, "leaf.l");
    assert_eq!(
        out.files[0].includes,
        [
            IncludeSite { line: 2, file: 1 },
            IncludeSite { line: 4, file: 2 }
        ]
    );
    assert_eq!(
        r.asked,
        [("leaf.l".to_string(), false), ("std.l".to_string(), true)]
    );
}

#[test]
fn include_in_a_false_branch_is_not_read() {
    let src = "#ifdef NOPE\n#include \"x.l\"\n#endif\n";
    let (out, errs, r) = run_with(src, &[("x.l", "X")], &Options::default());
    assert!(errs.is_empty());
    assert!(r.asked.is_empty());
    assert_eq!(out.files.len(), 1);
    assert_eq!(out.files[0].text, "\n\n\n");
}

#[test]
fn include_guard_and_a_file_included_twice() {
    let guarded = "#ifndef G\n#define G\nonce\n#endif\n";
    let src = "#include \"g.l\"\n#include \"g.l\"\n";
    let (out, errs, _) = run_with(src, &[("g.l", guarded)], &Options::default());
    assert!(errs.is_empty(), "{errs:#?}");
    assert_eq!(out.files.len(), 3);
    assert_eq!(out.files[1].text, "\n\nonce\n\n");
    assert_eq!(out.files[2].text, "\n\n\n\n");
}

#[test]
fn include_through_a_macro() {
    let (out, errs, _) = run_with(
        "#define FILE \"a.l\"\n#include FILE\n",
        &[("a.l", "a")],
        &Options::default(),
    );
    assert!(errs.is_empty(), "{errs:#?}");
    assert_eq!(out.files[0].text, "\n#include \"a.l\"\n");
}

// ---- errors, each with its span ----

#[test]
fn error_unterminated_if() {
    let (e, at) = one_error("#if 1\nA\n");
    assert_eq!(e.kind.code(), "lsys::preprocess::unterminated_if");
    assert_eq!(at, "#if 1");
}

#[test]
fn error_misplaced_else_elif_endif() {
    let (e, at) = one_error("A\n#else\n");
    assert_eq!((e.kind, at.as_str()), (ErrorKind::ElseWithoutIf, "#else"));
    let (e, at) = one_error("#elif 1\n");
    assert_eq!((e.kind, at.as_str()), (ErrorKind::ElifWithoutIf, "#elif 1"));
    let (e, at) = one_error("#endif  // x\n");
    assert_eq!((e.kind, at.as_str()), (ErrorKind::EndifWithoutIf, "#endif"));
    let (e, _) = one_error("#if 0\n#else\n#else\n#endif\n");
    assert_eq!(e.kind.code(), "lsys::preprocess::else_after_else");
    assert_eq!(e.span.start, "#if 0\n#else\n".len());
}

#[test]
fn error_macro_args() {
    let (e, at) = one_error("#define F(a,b) a\nx F(1) y");
    assert_eq!(e.kind.code(), "lsys::preprocess::macro_args");
    assert_eq!(at, "F(1)");
    assert!(
        e.message.contains("takes 2 arguments, but 1 was given"),
        "{}",
        e.message
    );
    // The invocation is left as written.
    let (out, _, _) = run_with("#define F(a,b) a\nx F(1) y", &[], &Options::default());
    assert_eq!(out.files[0].text, "\nx F(1) y");
}

#[test]
fn error_unterminated_call() {
    let (e, at) = one_error("#define F(a) a\nF(1,\n2");
    assert_eq!(e.kind.code(), "lsys::preprocess::unterminated_call");
    assert_eq!(at, "F");
    // A directive ends the search for `)`.
    let (e, _) = one_error("#define F(a) a\nF(1\n#define Z\n)");
    assert_eq!(e.kind, ErrorKind::UnterminatedCall);
}

#[test]
fn error_unterminated_comment() {
    let (e, at) = one_error("A /* x\ny");
    assert_eq!(e.kind.code(), "lsys::preprocess::unterminated_comment");
    assert_eq!(at, "/*");
}

#[test]
fn error_include_not_found() {
    let (e, at) = one_error("\n#include \"nope.l\"\n");
    assert_eq!(e.kind.code(), "lsys::preprocess::include_not_found");
    assert_eq!(at, "\"nope.l\"");
    assert!(e.message.contains("no such file: nope.l"), "{}", e.message);
}

#[test]
fn error_include_cycle_names_the_chain() {
    let files = [
        ("a.l", "#include \"b.l\"\n"),
        ("b.l", "x\n#include \"a.l\"\n"),
    ];
    let opts = Options {
        max_include_depth: 8,
        ..Options::default()
    };
    let (e, at) = one_error_with("#include \"a.l\"\n", &files, &opts);
    assert_eq!(e.kind.code(), "lsys::preprocess::include_depth");
    assert!(
        e.message.starts_with("include cycle: a.l -> b.l -> a.l"),
        "{}",
        e.message
    );
    assert_eq!(at, "\"a.l\"");
    // The deepest nesting allowed fits the stack.
    let opts = Options {
        max_include_depth: usize::MAX,
        ..Options::default()
    };
    let (e, _) = one_error_with("#include \"a.l\"\n", &files, &opts);
    assert!(e.message.contains("more than 256 deep"), "{}", e.message);
    // A file including itself twice stops after the first error, quickly.
    let (e, _) = one_error_with(
        "#include \"s.l\"\n",
        &[("s.l", "#include \"s.l\"\n#include \"s.l\"\n")],
        &Options::default(),
    );
    assert_eq!(e.kind, ErrorKind::IncludeDepth);
}

#[test]
fn error_bad_directive() {
    let (e, at) = one_error("#foo x\n");
    assert_eq!(e.kind.code(), "lsys::preprocess::bad_directive");
    assert_eq!(at, "foo");
    let (e, at) = one_error("#define 3 x\n");
    assert_eq!((e.kind, at.as_str()), (ErrorKind::BadDirective, "3"));
    let (e, _) = one_error("#include nothing\n");
    assert_eq!(e.kind, ErrorKind::BadDirective);
    let (e, at) = one_error("#define F(a,a) a\n");
    assert_eq!((e.kind, at.as_str()), (ErrorKind::BadDirective, "a"));
}

#[test]
fn error_if_expression() {
    let (e, at) = one_error("#if 1/0\n#endif");
    assert_eq!(e.kind.code(), "lsys::preprocess::if_expression");
    assert_eq!(at, "/");
    let (e, at) = one_error("#define W 0.5\n#if W > 1\n#endif");
    assert_eq!((e.kind, at.as_str()), (ErrorKind::IfExpression, "W"));
    assert!(e.help.is_some());
    let (e, at) = one_error("#if 1.5\n#endif");
    assert_eq!((e.kind, at.as_str()), (ErrorKind::IfExpression, "1.5"));
    let (e, _) = one_error("#if (1\n#endif");
    assert_eq!(e.kind, ErrorKind::IfExpression);
    let (e, _) = one_error("#if\n#endif");
    assert_eq!(e.kind, ErrorKind::IfExpression);
    let (e, at) = one_error("#if defined(\n#endif");
    assert_eq!((e.kind, at.as_str()), (ErrorKind::IfExpression, "defined("));
}

#[test]
fn elif_after_a_false_if_is_evaluated() {
    let (e, at) = one_error("#if 0\n#elif 1/0\n#endif");
    assert_eq!((e.kind, at.as_str()), (ErrorKind::IfExpression, "/"));
}

#[test]
fn deeply_nested_if_expression_is_an_error_not_a_crash() {
    let src = format!("#if {}1{}\n#endif", "(".repeat(5000), ")".repeat(5000));
    let (e, _) = one_error(&src);
    assert_eq!(e.kind, ErrorKind::IfExpression);
    assert!(e.message.contains("nested too deeply"), "{}", e.message);
    let src = format!("#if {}1\n#endif", "-".repeat(5000));
    assert_eq!(one_error(&src).0.kind, ErrorKind::IfExpression);
}

#[test]
fn errors_in_included_files_point_into_them() {
    let files = [("a.l", "x\n#include \"gone.l\"\n")];
    let (e, at) = one_error_with("#include \"a.l\"\n", &files, &Options::default());
    assert_eq!(
        (e.kind, e.file, at.as_str()),
        (ErrorKind::IncludeNotFound, 1, "\"gone.l\"")
    );
}

#[test]
fn error_directive_text() {
    let (e, at) = one_error("#error stop /* c */ here\n");
    assert_eq!(e.kind.code(), "lsys::preprocess::error_directive");
    assert_eq!(e.message, "#error stop here");
    assert_eq!(at, "#error stop /* c */ here");
    assert!(!e.warning);
}

#[test]
fn error_recursion_depth() {
    let opts = Options {
        max_expansion_depth: 5,
        ..Options::default()
    };
    let src = format!("#define F(x) [x]\n{}1{}", "F(".repeat(20), ")".repeat(20));
    let (out, errs, _) = run_with(&src, &[], &opts);
    assert!(!errs.is_empty());
    assert!(
        errs.iter()
            .all(|e| e.kind.code() == "lsys::preprocess::recursion"),
        "{errs:#?}"
    );
    assert_eq!(lines(&out.files[0].text), 2);
}

#[test]
fn error_recursion_exponential_growth() {
    // Each level doubles: 2^30 tokens would never finish.
    let mut src = String::from("#define A0 x x\n");
    for i in 1..30 {
        src.push_str(&format!("#define A{i} A{p} A{p}\n", p = i - 1));
    }
    src.push_str("A29\n");
    let (e, at) = one_error(&src);
    assert_eq!((e.kind, at.as_str()), (ErrorKind::Recursion, "A29"));
}

#[test]
fn expansion_budget_is_per_line() {
    // 2^14 tokens a line: the lines together exceed one line's budget (50000 in tests).
    let mut src = String::from("#define A0 x x\n");
    for i in 1..14 {
        src.push_str(&format!("#define A{i} A{p} A{p}\n", p = i - 1));
    }
    src.push_str("A13\nA13\nA13\nA13\n");
    let (out, errs, _) = run_with(&src, &[], &Options::default());
    assert!(errs.is_empty(), "{errs:#?}");
    let last = out.files[0].text.lines().last().unwrap_or("");
    assert_eq!(last.split(' ').count(), 1 << 14);
}

#[test]
fn conditionals_do_not_cross_file_boundaries() {
    let files = [("a.l", "#if 1\na\n")];
    let (out, errs, _) = run_with("#include \"a.l\"\n#else\nb\n", &files, &Options::default());
    let kinds: Vec<(ErrorKind, usize)> = errs.iter().map(|e| (e.kind, e.file)).collect();
    assert_eq!(
        kinds,
        [
            (ErrorKind::UnterminatedIf, 1),
            (ErrorKind::ElseWithoutIf, 0)
        ]
    );
    assert_eq!(out.files[0].text, "#include \"a.l\"\n\nb\n");
}

#[test]
fn deepest_allowed_expansion_fits_the_stack() {
    let opts = Options {
        max_expansion_depth: 100_000,
        ..Options::default()
    };
    let src = format!(
        "#define F(x) [x]\n{}1{}",
        "F(".repeat(1200),
        ")".repeat(1200)
    );
    let (out, errs, _) = run_with(&src, &[], &opts);
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert_eq!(errs[0].kind, ErrorKind::Recursion);
    assert_eq!(lines(&out.files[0].text), 2);
}

#[test]
fn warnings_redefinition_and_warning_directive() {
    let (e, at) = one_error("#define X 1\n#define X 1\n#define X 2\nX");
    assert_eq!(
        (e.kind.code(), at.as_str()),
        ("lsys::preprocess::redefined", "X")
    );
    assert!(e.warning);
    assert_eq!(e.span.start, "#define X 1\n#define X 1\n#define ".len());
    let (e, _) = one_error("#warning careful\n");
    assert!(e.warning && e.kind == ErrorKind::WarningDirective);
}

#[test]
fn diagnostic_renders_with_code_and_label() {
    let src = "#if 1\n";
    let (_, errs, _) = run_with(src, &[], &Options::default());
    let d = errs[0].to_diagnostic("root.l", std::sync::Arc::new(src.to_string()));
    let text = crate::diag::render_plain(&d);
    assert!(text.contains("lsys::preprocess::unterminated_if"), "{text}");
    assert!(text.contains("root.l:1:1"), "{text}");
}

// ---- robustness ----

/// Deterministic xorshift, so failures reproduce.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// Preprocesses `text` (every `#include` resolves to `text` itself) and
/// checks the invariants: line counts kept, spans inside their files.
fn check_invariants(text: &str) {
    struct Echo(String);
    impl Resolver for Echo {
        fn resolve(&mut self, _: &RawFile, name: &str, _: bool) -> Result<RawFile, String> {
            Ok(raw(name, &self.0))
        }
    }
    let opts = Options {
        max_include_depth: 4,
        max_expansion_depth: 20,
        ..Options::default()
    };
    let (out, errs) = preprocess(raw("root.l", text), &mut Echo(text.to_string()), &opts);
    for f in &out.files {
        assert_eq!(
            lines(&f.text),
            lines(&f.raw.text),
            "line count changed for {:?}",
            f.raw.text
        );
        for site in &f.includes {
            assert!(site.file < out.files.len() && site.line >= 1 && site.line <= lines(&f.text));
        }
    }
    for e in &errs {
        let src = &out.files[e.file].raw.text;
        assert!(
            src.get(e.span.clone()).is_some(),
            "bad span {e:?} in {src:?}"
        );
    }
}

const FRAGMENTS: &[&str] = &[
    "#define ",
    "#undef ",
    "#if ",
    "#ifdef ",
    "#elif ",
    "#else",
    "#endif",
    "#include \"i\"",
    "#include <",
    "#error ",
    "#",
    "##",
    "# ",
    "F",
    "G",
    "(",
    ")",
    ",",
    "...",
    "__VA_ARGS__",
    "defined",
    "\\\n",
    "\\",
    "\n",
    "\r\n",
    "/*",
    "*/",
    "//",
    "/",
    "\"",
    "<",
    ">",
    "-",
    "+",
    "?",
    ":",
    "0",
    "1",
    "1.5",
    "0x",
    "99999999999999999999",
    " ",
    "\t",
    "é",
    "F(x) x x",
    "A A",
    "&&",
    "||",
    "<<",
    "/ 0",
    "%",
];

#[test]
fn no_panic_on_fragment_soup() {
    let mut rng = Rng(0x5eed_1234_abcd_0001);
    for _ in 0..3000 {
        let n = 1 + rng.below(40);
        let text: String = (0..n)
            .map(|_| FRAGMENTS[rng.below(FRAGMENTS.len())])
            .collect();
        check_invariants(&text);
    }
}

#[test]
fn no_panic_on_random_bytes() {
    let mut rng = Rng(0x0dd_ba11_cafe_f00d);
    for _ in 0..2000 {
        let n = rng.below(80);
        let bytes: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
        check_invariants(&String::from_utf8_lossy(&bytes));
    }
}

const SAMPLE: &str = "/* A small cpfg-like model */\n\
#define STEPS 8\n\
#define ANG 22.5 // degrees\n\
#define BR(a, l) [+(a) F(l) LEAF]\n\
#define LEAF ~l(1)\n\
#if STEPS > 4 && defined(ANG)\n\
#define LONG 1\n\
#else\n\
#define LONG 0\n\
#endif\n\
Lsystem: 1\n\
derivation length: STEPS\n\
Axiom: A(1)\n\
A(x) : x < STEPS --> F(x) BR(ANG,\n\
   x/2) #(w) /(137.5) \\\n\
   A(x+1)\n\
#include \"leaf.l\"\n\
endlsystem\n";

#[test]
fn no_panic_on_truncations_of_a_valid_file() {
    let (out, errs, _) = run_with(SAMPLE, &[("leaf.l", "")], &Options::default());
    assert!(errs.is_empty(), "{errs:#?}");
    let text = &out.files[0].text;
    assert!(
        text.contains("F(x) [+(22.5) F(x/2) ~l(1)] #(w) /(137.5) A(x+1)\n\n\n#include"),
        "{text}"
    );
    for (i, _) in SAMPLE.char_indices() {
        check_invariants(&SAMPLE[..i]);
    }
}

#[test]
fn line_count_is_kept_for_every_input() {
    let inputs = [
        "",
        "\n",
        "A",
        "A\r\nB\r\n",
        "#define X \\\n  1\nX\n",
        "#define M(a,b) a b\nM(1,\n\n\n2)\nend\n",
        "a /* x\n\n */ b\n",
        "#if 0\nno\n#endif\n",
        "#define E\nE\n\\\n\\\n",
        SAMPLE,
    ];
    for text in inputs {
        let (out, _, _) = run_with(text, &[("leaf.l", "L\n")], &Options::default());
        for f in &out.files {
            assert_eq!(
                lines(&f.text),
                lines(&f.raw.text),
                "{text:?} -> {:?}",
                f.text
            );
        }
    }
}
