//! `:undo`: the session's edits (typed productions, `:drop`, `:axiom`,
//! `:set`, `:seed`) -> a stack of what the grammar was before each, and
//! the last one taken back. Input: the session before and after one
//! input; output: the edit recorded, or the grammar restored and derived
//! to the same step. `:load` and `:reload` start over: they are not edits
//! and cannot be undone.

use super::{Out, Session, Source};

/// Everything an edit can change.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct EditState {
    /// The working grammar's source, text and whether it differs from
    /// its file; `None` before there is one.
    grammar: Option<(Source, String, bool)>,
    overrides: Vec<(String, String)>,
    seed: Option<u64>,
    typed: Vec<String>,
}

/// One undoable edit: the input that made it and the state before it.
#[derive(Clone, Debug)]
pub(super) struct Edit {
    input: String,
    before: EditState,
}

impl Session {
    pub(super) fn edit_state(&self) -> EditState {
        EditState {
            grammar: self
                .grammar
                .as_ref()
                .map(|g| (g.source.clone(), g.text.clone(), g.edited)),
            overrides: self.overrides.clone(),
            seed: self.opts.seed,
            typed: self.typed.clone(),
        }
    }

    /// After `input` ran: remembers the state before it when it changed
    /// the grammar, the defines or the seed. `:load`, `:reload` and
    /// `:undo` are not recorded; the first two clear the stack.
    pub(super) fn record_edit(&mut self, input: &str, before: EditState, command: Option<&str>) {
        match command {
            Some("load" | "reload") => self.undo.clear(),
            Some("undo") => {}
            _ if self.edit_state() != before => self.undo.push(Edit {
                input: input.trim().to_string(),
                before,
            }),
            _ => {}
        }
    }

    /// `:undo`: takes back the last edit.
    pub fn undo(&mut self) -> Out {
        let Some(edit) = self.undo.pop() else {
            return Err("nothing to undo: `:undo` takes back productions typed, `:drop`, `:axiom`, `:set` and `:seed` (not `:load` or `:reload`)".into());
        };
        let before = edit.before;
        self.opts.seed = before.seed;
        self.overrides = before.overrides;
        self.typed = before.typed;
        let Some((source, text, edited)) = before.grammar else {
            self.grammar = None;
            self.pos = 0;
            return Ok(format!("undid `{}`: there is no grammar again", edit.input));
        };
        let comp = match self.compile(&source, &text, &self.overrides) {
            Ok(c) => c,
            // It compiled before the edit; a file it includes may have
            // changed since.
            Err(e) => return Err(format!("cannot undo `{}`:\n{e}", edit.input)),
        };
        let keep = self.pos;
        let rest = self.install(source, text, comp, edited)?;
        let rest = if self.pos == keep {
            rest
        } else {
            rest + &format!(" (step {keep} is beyond the grammar now)")
        };
        Ok(format!("undid `{}`\n{rest}", edit.input))
    }
}
