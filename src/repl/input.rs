//! What the user typed, before it is run: text in, whether the next line
//! continues it ([`needs_more`]) and what kind of input it is
//! ([`classify`]). Pure functions, shared by the line editor's validator
//! and the reader of piped input.

/// The arrows the language accepts between a head and a successor.
const ARROWS: [&str; 6] = ["-->", "->", "−−>", "−>", "→", "⟶"];

/// What one input is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Kind<'a> {
    /// Nothing but blanks or a `//` comment.
    Empty,
    /// `:name args`.
    Command { name: &'a str, args: &'a str },
    /// A statement: a production (`A --> B`, `A : B`) or a header.
    Statement,
    /// Modules to rewrite once (`A(3) B`).
    Modules,
}

/// Classifies one (possibly multi-line) input.
pub fn classify(text: &str) -> Kind<'_> {
    let t = text.trim();
    if t.is_empty() || t.starts_with("//") {
        return Kind::Empty;
    }
    // What a newcomer types to leave: `quit` and `exit` leave as `:quit`
    // does, instead of being rewritten as a string of one-letter modules.
    if matches!(t, "quit" | "exit") {
        return Kind::Command {
            name: "quit",
            args: "",
        };
    }
    if let Some(rest) = t.strip_prefix(':') {
        let (name, args) = rest.split_once(char::is_whitespace).unwrap_or((rest, ""));
        return Kind::Command {
            name,
            args: args.trim(),
        };
    }
    if is_statement(t) {
        Kind::Statement
    } else {
        Kind::Modules
    }
}

/// Whether `text` has the shape of a statement: an arrow, a `:` (headers
/// and the paper's productions; modules never contain one) or a
/// directive.
pub fn is_statement(text: &str) -> bool {
    let t = text.trim_start();
    t.starts_with('#') || t.contains(':') || ARROWS.iter().any(|a| t.contains(a))
}

/// Whether input that ends with `text` is unfinished: it ends inside
/// brackets or parentheses (outside comments), or with a backslash.
/// Commands are always complete.
pub fn needs_more(text: &str) -> bool {
    let t = text.trim();
    if t.is_empty() || t.starts_with(':') {
        return false;
    }
    if t.ends_with('\\') {
        return true;
    }
    depth(t) > 0
}

/// Open brackets and parentheses minus closed ones, skipping comments.
fn depth(text: &str) -> i64 {
    let mut d = 0i64;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        break;
                    }
                }
            }
            '/' if chars.peek() == Some(&'*') => {
                chars.next();
                let mut prev = ' ';
                for c in chars.by_ref() {
                    if prev == '*' && c == '/' {
                        break;
                    }
                    prev = c;
                }
            }
            '[' | '(' => d += 1,
            ']' | ')' => d -= 1,
            _ => {}
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds() {
        assert_eq!(classify("  "), Kind::Empty);
        for leave in ["quit", " exit "] {
            assert_eq!(
                classify(leave),
                Kind::Command {
                    name: "quit",
                    args: ""
                }
            );
        }
        assert_eq!(classify("quit F"), Kind::Modules);
        assert_eq!(classify("// note"), Kind::Empty);
        assert_eq!(
            classify(":step 3"),
            Kind::Command {
                name: "step",
                args: "3"
            }
        );
        assert_eq!(
            classify(":rules"),
            Kind::Command {
                name: "rules",
                args: ""
            }
        );
        assert_eq!(classify("A(x) --> B(x+1)"), Kind::Statement);
        assert_eq!(classify("A(β) : β < 3  F A(β+1)"), Kind::Statement);
        assert_eq!(classify("X → F"), Kind::Statement);
        assert_eq!(classify("A(3) B"), Kind::Modules);
        assert_eq!(classify("F [ + F ] F"), Kind::Modules);
    }

    #[test]
    fn continuation() {
        assert!(needs_more("A --> F [+A"));
        assert!(needs_more("A(x) --> B(x,"));
        assert!(needs_more("A --> F \\"));
        assert!(!needs_more("A --> F [+A] F"));
        assert!(!needs_more("A --> F // [ in a comment"));
        assert!(!needs_more("A --> F /* ( */ G"));
        assert!(!needs_more(":show [0..3"));
        assert!(!needs_more("A --> F ]"));
    }
}
