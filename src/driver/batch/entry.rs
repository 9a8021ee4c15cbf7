//! One line of `index.jsonl`: what became of one item -> its id, status,
//! output file and that file's SHA-256, the model's figures, the time it
//! took, and for a failed item its diagnostics as plain data.

use serde::{Deserialize, Serialize};

use crate::diag::Message;

/// What became of one item.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Entry {
    pub id: String,
    pub status: Status,
    /// The output file's name in the output folder (an OBJ's `.mtl` is
    /// beside it, with the same stem); `null` for a failed item.
    pub output: Option<String>,
    /// The output file's SHA-256, in hex.
    pub sha256: Option<String>,
    /// Modules of the string the turtle drew (`null` for a guided scene,
    /// whose seeds are strings of their own).
    pub modules: Option<usize>,
    pub triangles: Option<usize>,
    /// The box around everything drawn; `null` when nothing is.
    pub bounds: Option<Bounds>,
    /// Milliseconds the item took: build, write and hash.
    pub ms: f64,
    /// Why it failed (errors first, then warnings), for a failed item.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub diagnostics: Vec<ItemDiagnostic>,
}

/// Whether the item was built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    Ok,
    Error,
}

/// The box around a model, as `--stats` gives it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Bounds {
    pub min: [f32; 3],
    pub max: [f32; 3],
}

/// One diagnostic of a failed item: [`Message`] as JSON.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ItemDiagnostic {
    pub code: Option<String>,
    /// `error`, `warning` or `advice`.
    pub severity: String,
    pub file: Option<String>,
    pub line: Option<usize>,
    pub column: Option<usize>,
    pub message: String,
    pub help: Option<String>,
}

impl From<Message> for ItemDiagnostic {
    fn from(m: Message) -> ItemDiagnostic {
        ItemDiagnostic {
            code: m.code,
            severity: m.severity.as_str().to_string(),
            file: m.file,
            line: m.line,
            column: m.column,
            message: m.message,
            help: m.help,
        }
    }
}

impl std::fmt::Display for ItemDiagnostic {
    /// The short form of [`Message`]: `file:line:column:
    /// severity[code]: message`, each part present when known.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let place = match (&self.file, self.line, self.column) {
            (Some(file), Some(line), Some(column)) => Some((file.as_str(), line, column)),
            _ => None,
        };
        crate::diag::write_short(
            f,
            place,
            &self.severity,
            self.code.as_deref(),
            &self.message,
        )
    }
}

impl Entry {
    pub fn is_ok(&self) -> bool {
        self.status == Status::Ok
    }

    /// The entry as one line of the index, newline included.
    pub fn to_line(&self) -> String {
        // An entry holds strings, numbers and options only: it always
        // serialises (f32 infinities become `null`).
        let mut line = serde_json::to_string(self).expect("an entry serialises");
        line.push('\n');
        line
    }
}
