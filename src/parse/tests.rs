//! Parser tests: statements, left contexts, the paper form, tables,
//! headers, limits.

use super::*;
use crate::source::Origin;

fn errors(text: String) -> Vec<ParseError> {
    let file = SourceFile::new("t.lsys", Origin::Memory, text);
    parse(0, &file).1
}

/// (left context length, predecessor length, successor length) of
/// each production of `text`, which must parse.
fn heads(text: &str) -> Vec<(usize, usize, usize)> {
    let file = SourceFile::new("t.lsys", Origin::Memory, text.to_string());
    let (ast, errors) = parse(0, &file);
    assert!(errors.is_empty(), "{text}: {errors:?}");
    ast.items
        .iter()
        .filter_map(|item| match item {
            ast::Item::Production(p) => Some((p.lctx.len(), p.pred.len(), p.succ.len())),
            _ => None,
        })
        .collect()
}

/// The look-ahead for a left context ends at the end of the line, but
/// passes over a block comment and a `\` line join inside the head; a
/// `<` (roll) in a successor's continuation lines is no left context.
#[test]
fn left_contexts_are_found_within_their_line() {
    assert_eq!(heads("A B < C --> D\n"), vec![(2, 1, 1)]);
    assert_eq!(heads("A \\\n B < C --> D\n"), vec![(2, 1, 1)]);
    assert_eq!(heads("A /* one\n two */ B < C --> D\n"), vec![(2, 1, 1)]);
    assert_eq!(
        heads("A --> B\n  < C\n  D < E\nF : G\n"),
        vec![(0, 1, 6), (0, 1, 1)]
    );
    assert_eq!(heads("A --> B\nC < D --> E\n"), vec![(0, 1, 1), (1, 1, 1)]);
}

/// The paper's form (`A : successor`) is told from the arrow form by
/// an arrow later on the same line; an arrow in a comment does not
/// count, one after a `\` line join does.
#[test]
fn the_papers_form_is_told_by_an_arrow_on_its_line() {
    assert_eq!(
        heads("A : B C // not --> here\nD --> E\n"),
        vec![(0, 1, 2), (0, 1, 1)]
    );
    assert_eq!(heads("A : B /* a --> b\n */ C\n"), vec![(0, 1, 2)]);
    assert_eq!(heads("A(x) : x > 1 \\\n --> B C\n"), vec![(0, 1, 2)]);
    assert_eq!(heads("A(x) : x > 1 B C\n"), vec![(0, 1, 2)]);
}

/// An indented line that is a header ends the successor above it.
/// `may_start` (grammar/lsys.pest) tests a continuation line for a
/// statement only if it holds a `:`, `>` or arrow or begins with the
/// letter of a header that needs no `:`: each header of the grammar is
/// listed here as one or the other, so that a new one must be too.
#[test]
fn indented_headers_end_a_successor() {
    let grammar = include_str!("../../grammar/lsys.pest");
    let alternatives: String = grammar
        .lines()
        .skip_while(|l| !l.starts_with("header = _{"))
        .skip(1)
        .take_while(|l| !l.starts_with('}'))
        .collect();
    let mut headers: Vec<&str> = alternatives
        .split(|c: char| c == '|' || c.is_whitespace())
        .filter(|w| !w.is_empty())
        .collect();
    headers.sort_unstable();
    let without_colon = [
        ("decomposition_h", "decomposition"),
        ("endlsystem_h", "endlsystem"),
        ("homomorphism_h", "homomorphism"),
        ("module_h", "module X(a)"),
        ("ring_h", "ring lsystem"),
    ];
    let with_colon = [
        "angle_h",
        "axiom_h",
        "block_h",
        "colour_h",
        "consider_h",
        "dialect_h",
        "dlength_h",
        "environment_h",
        "ignore_h",
        "lsystem_h",
        "maxdepth_h",
        "seed_h",
        "step_h",
        "texture_h",
        "width_h",
    ];
    let mut listed: Vec<&str> = without_colon.iter().map(|h| h.0).collect();
    listed.extend(with_colon);
    listed.sort_unstable();
    assert_eq!(
        headers, listed,
        "classify the new header here and, if it needs no `:`, add its first letter to `may_start`"
    );
    for (_, header) in without_colon {
        let mut upper = header.to_string();
        upper[..1].make_ascii_uppercase();
        for h in [header.to_string(), upper] {
            let text = format!("A --> B C\n    {h}\n");
            let file = SourceFile::new("t.lsys", Origin::Memory, text.clone());
            let (ast, _) = parse(0, &file);
            let succ = ast.items.iter().find_map(|item| match item {
                ast::Item::Production(p) => Some(p.succ.len()),
                _ => None,
            });
            assert_eq!(succ, Some(2), "{text:?}: the header joined the successor");
            assert!(ast.items.len() >= 2, "{text:?}: {:?}", ast.items.len());
        }
    }
}

/// A table's plain numbers (taken without the expression rule) are
/// the numbers their expressions were, spanning only their text; any
/// other value is an expression as before.
#[test]
fn table_numbers_are_their_expressions() {
    let text = "#define t[9] {1, 2.5 , 3e2,\n 4 /* c */, 5+1, -2, 7 ? 1 : 0, .5,\n {8}}\n";
    let file = SourceFile::new("t.lsys", Origin::Memory, text.to_string());
    let (ast, errors) = parse(0, &file);
    assert!(errors.is_empty(), "{errors:?}");
    let Some(ast::Item::Define(ds)) = ast.items.first() else {
        panic!("a define")
    };
    let (values, _) = ds[0].elems.as_ref().expect("a table");
    let shown: Vec<(String, &str)> = values
        .iter()
        .map(|v| {
            let kind = match &v.kind {
                ast::ExprKind::Num(n) => format!("{n}"),
                ast::ExprKind::Binary(..) => "binary".to_string(),
                ast::ExprKind::Unary(..) => "unary".to_string(),
                ast::ExprKind::Ternary(..) => "ternary".to_string(),
                other => format!("{other:?}"),
            };
            (kind, &text[v.span.start as usize..v.span.end as usize])
        })
        .collect();
    let expected = [
        ("1", "1"),
        ("2.5", "2.5"),
        ("300", "3e2"),
        ("4", "4"),
        ("binary", "5+1"),
        ("unary", "-2"),
        ("ternary", "7 ? 1 : 0"),
        ("0.5", ".5"),
        ("8", "8"),
    ];
    let expected: Vec<(String, &str)> = expected.iter().map(|(k, t)| (k.to_string(), *t)).collect();
    assert_eq!(shown, expected);
}

/// Input that would exhaust the stack is refused before parsing; just
/// below the limits it parses (on a 64 MiB stack, as the binary runs
/// with 256 MiB: a debug build's frames are large).
#[test]
fn deep_or_long_expressions_are_refused_not_crashed_on() {
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(limits)
        .unwrap()
        .join()
        .unwrap();
}

fn limits() {
    let parens = |n| format!("Axiom: A({}1{})\n", "(".repeat(n), ")".repeat(n));
    let negs = |n| format!("Axiom: A({}1)\n", "-".repeat(n));
    let sum = |n| format!("#define s {}\nAxiom: A(s)\n", vec!["1"; n].join("+"));
    for (ok, bad) in [
        (parens(MAX_NESTING - 1), parens(100_000)),
        (negs(MAX_OPERATORS), negs(100_000)),
        (sum(MAX_OPERATORS), sum(100_000)),
    ] {
        assert!(errors(ok).is_empty());
        let e = errors(bad);
        assert_eq!(e.len(), 1);
        assert!(matches!(e[0], ParseError::TooDeep { .. }), "{:?}", e[0]);
    }
    // Long module strings are not expressions: no limit.
    assert!(errors(format!("Axiom: {}\n", "F+".repeat(100_000))).is_empty());
}

/// Each standard library file's stored tree (build.rs) is the tree its
/// text parses to, with its spans in the file it is loaded as.
#[test]
fn stored_library_trees_are_the_parsed_ones() {
    for &crate::stdlib::StdFile { name, text, .. } in crate::stdlib::FILES {
        let file = SourceFile::new(format!("std:{name}"), Origin::Std(name.into()), text);
        let (fresh, errors, _) = parse_statements(7, &file, None);
        assert!(errors.is_empty(), "{name}: {errors:?}");
        assert!(
            matches!(stored::reuse(7, text), Some(stored::Shared::Whole(_))),
            "{name}"
        );
        let (read, errors) = parse(7, &file);
        assert!(errors.is_empty(), "{name}: {errors:?}");
        assert_eq!(format!("{read:?}"), format!("{fresh:?}"), "{name}");
        assert!(
            format!("{read:?}").contains("7@"),
            "{name}: spans in file 7"
        );
    }
}

/// The tree and the diagnostics of `text`, parsed whole.
fn parsed_whole(text: &str) -> (String, Vec<String>) {
    let file = SourceFile::new("t.lsys", Origin::Memory, text.to_string());
    let (tree, mut errors, _) = parse_statements(5, &file, None);
    errors.extend(slash_comments(&file, 5));
    errors.extend(headers::misspelt_headers(&file, 5));
    (format!("{tree:?}"), described(&errors))
}

/// Each error's message and where it is, to compare two parses' errors.
fn described(errors: &[ParseError]) -> Vec<String> {
    errors
        .iter()
        .map(|e| format!("{e} {:?}", e.offset()))
        .collect()
}

/// Texts made from a library file by an edit anywhere (a style's tables in
/// place of the Pailou's, a character more or less, a line joined to or
/// split from a statement, a mistake) parse to what they parse to whole,
/// with the statements they share read from the stored tree.
#[test]
fn texts_made_from_library_files_parse_as_themselves() {
    let lib = crate::stdlib::get("pailou").unwrap();
    let start = lib.find("// <layout>").unwrap();
    let end = lib.find("// </layout>").unwrap();
    let mut texts = vec![
        format!(
            "{}// <layout> ours\n#define exists[1..2, 1..2] {{1, 0, 1, 0}}\n{}",
            &lib[..start],
            &lib[end..]
        ),
        format!("{}{}", &lib[..start], &lib[end..]),
        format!("{lib}\nA --> B\n"),
        lib.replacen("#define", "#define  ", 1),
    ];
    let edits = ["", "x", "\n", "\n    F(1)", "\n#define Q 1\n", " ->"];
    let mut at = 0;
    while at < lib.len() {
        at = (at + 211).min(lib.len());
        while !lib.is_char_boundary(at) {
            at += 1;
        }
        for (k, edit) in edits.iter().enumerate() {
            let cut = if k == 0 {
                lib[at..].chars().next().map_or(0, char::len_utf8)
            } else {
                0
            };
            texts.push(format!("{}{edit}{}", &lib[..at], &lib[at + cut..]));
        }
    }
    let mut shared = 0;
    for text in &texts {
        let file = SourceFile::new("t.lsys", Origin::Memory, text.clone());
        let reuse = stored::reuse(5, text);
        if let Some(stored::Shared::Parts(r)) = &reuse {
            shared += r.first.len() + r.last.len();
        }
        let (tree, errors) = parse(5, &file);
        let whole = parsed_whole(text);
        assert_eq!((format!("{tree:?}"), described(&errors)), whole, "{text}");
    }
    // Most statements of most texts were read.
    assert!(
        shared > texts.len() * 40,
        "{shared} statements shared in {} texts",
        texts.len()
    );
}

/// Limits apply to the library's files as to any other.
#[test]
fn limits_reach_stored_trees() {
    let text = crate::stdlib::get("pailou").unwrap();
    let file = SourceFile::new("std:pailou", Origin::Std("pailou".into()), text);
    let tight = Limits {
        max_nesting: 2,
        max_operators: MAX_OPERATORS,
    };
    let (tree, errors) = parse_limited(0, &file, tight);
    assert!(tree.items.is_empty());
    assert_eq!(errors.len(), 1, "{errors:?}");
}
