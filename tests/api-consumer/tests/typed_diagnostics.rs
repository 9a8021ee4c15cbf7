//! Diagnostics as a caller of the library reads them: each one's code,
//! severity, file, line, column, message and help as plain values, and
//! the one-line `Display` of a failure, through the public API only.

use lsys::{Diagnostics, Grammar, Level, Message};

/// An unknown name on line 3 and one on line 4.
const TWO_MISTAKES: &str =
    "derivation length: 2\naxiom: F(1) G(2)\nF(a) --> F(a + b)\nG(x) --> G(x * c)\n";

fn failure(name: &str, text: &str) -> Diagnostics {
    match Grammar::from_str(name, text) {
        Ok(g) => panic!("{name} compiled: {g:?}"),
        Err(e) => e,
    }
}

/// Every field, one a line, as a caller would print them.
fn fields(m: &Message) -> String {
    let or_none = |s: Option<String>| s.unwrap_or_else(|| "(none)".to_string());
    format!(
        "code: {}\nseverity: {}\nfile: {}\nline: {}\ncolumn: {}\nmessage: {}\nhelp: {}\n",
        or_none(m.code.clone()),
        m.severity,
        or_none(m.file.clone()),
        or_none(m.line.map(|l| l.to_string())),
        or_none(m.column.map(|c| c.to_string())),
        m.message,
        or_none(m.help.clone()),
    )
}

#[test]
fn each_mistake_as_typed_fields() {
    let err = failure("plant.lsys", TWO_MISTAKES);
    assert_eq!(err.len(), 2);
    assert!(err.has_errors());
    let messages: Vec<Message> = err.messages().collect();
    assert!(messages.iter().all(|m| m.severity == Level::Error));
    let text: Vec<String> = messages.iter().map(fields).collect();
    insta::assert_snapshot!(text.join("\n"));
}

#[test]
fn a_mistake_without_a_place_in_the_file() {
    let err = match Grammar::options()
        .define("ANGEL", 30)
        .from_str("plant.lsys", "#define ANGLE 22.5\naxiom: F\n")
    {
        Ok(g) => panic!("compiled: {g:?}"),
        Err(e) => e,
    };
    insta::assert_snapshot!(fields(&err.messages().next().unwrap()));
}

#[test]
fn a_failure_displays_as_one_line_with_its_place() {
    let two = failure("plant.lsys", TWO_MISTAKES);
    let one = failure("bad.lsys", "axiom: A(1\n");
    insta::assert_snapshot!(format!("{two}\n{one}"));
}

#[test]
fn each_message_renders_as_the_command_line_does() {
    let err = failure("plant.lsys", TWO_MISTAKES);
    let m = err.messages().nth(1).unwrap();
    insta::assert_snapshot!(m.rendered());
}
