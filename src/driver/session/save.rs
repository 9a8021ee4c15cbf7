//! `:save [FILE]`: the session's grammar (the root file's text with the
//! productions typed, dropped or changed, and the defines set with `:set`
//! or `-D` written into its own `#define` lines) in, a file written
//! atomically out; the session then goes on from that file.

use std::path::{Path, PathBuf};

use super::{grammar, Out, Session, Source};

impl Session {
    /// `:save [FILE]`: without a name, over the file loaded.
    pub fn save(&mut self, arg: &str) -> Out {
        let g = self.grammar()?;
        let path = match (arg.trim(), &g.source) {
            ("", Source::File(p)) => p.clone(),
            ("", other) => {
                return Err(format!(
                    "`:save` needs a file name here: {} is not a file of yours (`:save FILE`)",
                    other.name()
                ))
            }
            (a, _) => PathBuf::from(a),
        };
        // Saving over the grammar's own file is what `:save` is for; over
        // a file it includes, it would lose that file.
        let root = match &g.source {
            Source::File(p) => std::fs::canonicalize(p).ok(),
            _ => None,
        };
        let others: Vec<PathBuf> = g
            .comp
            .program
            .sources
            .disk_paths()
            .into_iter()
            .filter(|p| std::fs::canonicalize(p).ok() != root)
            .collect();
        crate::export::atomic::refuse_inputs(&path, &others)
            .map_err(|e| format!("{e}: `:save` another name, or edit that file itself"))?;
        let (text, unwritten) = grammar::set_defines(&g.text, &self.overrides);
        let old = g.source.name();
        crate::export::atomic::write_file(&path, |w| w.write_all(text.as_bytes()))
            .map_err(|e: std::io::Error| format!("cannot save {}: {e}", path.display()))?;
        let mut said = format!("saved {} ({} lines)", path.display(), text.lines().count());
        if !unwritten.is_empty() {
            let list: Vec<String> = unwritten.iter().map(|(n, v)| format!("{n}={v}")).collect();
            said.push_str(&format!(
                "; not written, as the file has no `#define NAME value` line of its own for them (they stay set here; give them with -D): {}",
                list.join(" ")
            ));
        }
        self.go_on_from(&path, text, unwritten, &old, said)
    }

    /// The session continues from the saved file, when it compiles from
    /// its new place (its includes are relative to it).
    fn go_on_from(
        &mut self,
        path: &Path,
        text: String,
        unwritten: Vec<(String, String)>,
        old: &str,
        said: String,
    ) -> Out {
        let source = Source::File(path.to_path_buf());
        match self.compile(&source, &text, &unwritten) {
            Ok(comp) => {
                self.overrides = unwritten;
                self.typed.clear();
                self.target = Some(source.clone());
                let rest = self.install(source, text, comp, false)?;
                Ok(format!("{said}\n{rest}"))
            }
            Err(errors) => Ok(format!(
                "{said}\nit does not compile from its new place, so the session goes on with {old}:\n{errors}"
            )),
        }
    }
}
