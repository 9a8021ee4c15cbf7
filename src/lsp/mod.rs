//! `lsys lsp`: a language server for `.lsys` grammars and cpfg `.l`
//! models. Input: LSP messages (stdio, or any [`lsp_server::Connection`]);
//! output: diagnostics from the same compiler as `lsys check`, hovers,
//! definitions, references, renames, completions, semantic tokens,
//! document symbols and links, inlay hints, quick fixes and code lenses
//! with production firing counts. See docs/editors.md.
//!
//! Unlike the other front ends, which go through the API and the driver
//! (`tests/architecture.rs`), the server reaches into the parser, loader
//! and resolver: it must answer on text that does not compile (hovers,
//! completions and symbols of a half-typed file), which no API for whole
//! grammars gives.
//!
//! The structure is ruff's and ty's: one synchronous loop (`server.rs`)
//! owns the open documents (text and version) and applies edits in the
//! order they arrive; analyses run on worker threads once no message is
//! waiting (a burst of keystrokes is compiled once), within a wall-clock
//! budget; requests are answered from the last finished analysis, never
//! waiting for a running one; diagnostics are published with the version
//! they were computed for. `transport.rs` reads and writes the stdio
//! stream itself, so that no malformed message ends the server.
//!
//! ```text
//! position     byte offsets <-> LSP (UTF-16) positions
//! index        every named occurrence of the model (modules, commands,
//!              defines, parameters, components, includes), from the syntax
//! analysis     a document -> load + compile + index
//! diagnostics  compiler diagnostics -> LSP diagnostics, quick fixes
//! hover, navigate, complete, inlay, lens   the requests
//! server       the loop
//! transport    stdio framing, lenient: malformed input answered or skipped
//! ```

mod analysis;
mod complete;
mod diagnostics;
mod hover;
mod index;
mod inlay;
mod lens;
mod navigate;
pub mod position;
mod server;
pub mod transport;

pub use server::{capabilities, serve};

/// Runs the server over standard input and output until the client asks
/// it to exit; the process's exit code.
pub fn run_stdio(options: crate::GrammarOptions) -> i32 {
    // Our own framing (transport.rs): lsp-server's stdio reader exits on
    // the first malformed message.
    match transport::stdio(|conn| serve(conn, options.build.source)) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("lsys lsp: {e}");
            1
        }
    }
}
