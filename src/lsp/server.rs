//! The server's main loop. Input: messages from an
//! [`lsp_server::Connection`]; output: responses and notifications on it.
//! The loop owns the state (open documents: text, version, analysis),
//! applies document edits in arrival order, analyses changed documents
//! once the queue is empty (or before answering a request), and answers
//! each request against the current analysis of its document.

use std::collections::BTreeMap;
use std::error::Error;
use std::panic::{self, AssertUnwindSafe};

use lsp_server::{Connection, Message, Notification, Request, Response};
use lsp_types::notification::{self as notif, Notification as _};
use lsp_types::request::{self as req, Request as _};
use lsp_types::*;
use serde_json::Value;

use super::analysis::{Analysis, ROOT};
use super::position::LineIndex;
use super::{complete, diagnostics, hover, inlay, lens, navigate};
use crate::load;

type Result<T> = std::result::Result<T, Box<dyn Error + Send + Sync>>;

struct Document {
    version: i32,
    text: String,
    /// `None` until analysed after the last edit.
    analysis: Option<Analysis>,
    /// Analysing this version panicked (a bug): wait for the next edit.
    crashed: bool,
}

struct Server<'c> {
    conn: &'c Connection,
    opts: load::Options,
    docs: BTreeMap<Url, Document>,
    /// Analyses made stale by an edit, dropped only after the new
    /// diagnostics are published: freeing a large model's syntax tree and
    /// program takes a few milliseconds the editor need not wait for.
    stale: Vec<Analysis>,
}

impl Document {
    /// Forgets the analysis (the text changed), keeping it in `stale`.
    fn invalidate(&mut self, stale: &mut Vec<Analysis>) {
        stale.extend(self.analysis.take());
    }
}

/// What the server offers.
pub fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Kind(
            TextDocumentSyncKind::INCREMENTAL,
        )),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        rename_provider: Some(OneOf::Right(RenameOptions {
            prepare_provider: Some(true),
            work_done_progress_options: WorkDoneProgressOptions::default(),
        })),
        completion_provider: Some(CompletionOptions {
            trigger_characters: Some(vec!["~".into(), "@".into(), "<".into(), "\"".into()]),
            ..CompletionOptions::default()
        }),
        document_symbol_provider: Some(OneOf::Left(true)),
        document_link_provider: Some(DocumentLinkOptions {
            resolve_provider: Some(false),
            work_done_progress_options: WorkDoneProgressOptions::default(),
        }),
        semantic_tokens_provider: Some(SemanticTokensServerCapabilities::SemanticTokensOptions(
            SemanticTokensOptions {
                legend: complete::legend(),
                full: Some(SemanticTokensFullOptions::Bool(true)),
                range: None,
                work_done_progress_options: WorkDoneProgressOptions::default(),
            },
        )),
        code_action_provider: Some(CodeActionProviderCapability::Options(CodeActionOptions {
            code_action_kinds: Some(vec![CodeActionKind::QUICKFIX]),
            ..CodeActionOptions::default()
        })),
        inlay_hint_provider: Some(OneOf::Left(true)),
        code_lens_provider: Some(CodeLensOptions {
            resolve_provider: Some(false),
        }),
        ..ServerCapabilities::default()
    }
}

/// Serves one client on `conn`: the initialize handshake, then the loop
/// until `shutdown` and `exit`.
pub fn serve(conn: Connection, opts: load::Options) -> Result<()> {
    let (id, _params) = conn.initialize_start()?;
    let result = InitializeResult {
        capabilities: capabilities(),
        server_info: Some(ServerInfo {
            name: "lsys".into(),
            version: Some(env!("CARGO_PKG_VERSION").into()),
        }),
    };
    conn.initialize_finish(id, serde_json::to_value(result)?)?;
    let mut server = Server {
        conn: &conn,
        opts,
        docs: BTreeMap::new(),
        stale: Vec::new(),
    };
    server.run()
}

impl Server<'_> {
    fn run(&mut self) -> Result<()> {
        let mut shut_down = false;
        while let Ok(msg) = self.conn.receiver.recv() {
            match msg {
                Message::Request(r) => {
                    if r.method == req::Shutdown::METHOD {
                        // Answered, then the loop waits for `exit` (or the
                        // client closing the pipe). Clients may ask twice.
                        shut_down = true;
                        self.conn.sender.send(Response::new_ok(r.id, ()).into())?;
                        continue;
                    }
                    if shut_down {
                        let e = Response::new_err(
                            r.id,
                            lsp_server::ErrorCode::InvalidRequest as i32,
                            "the server is shutting down".into(),
                        );
                        self.conn.sender.send(e.into())?;
                        continue;
                    }
                    self.analyse_pending()?;
                    let response = self.request(r);
                    self.conn.sender.send(response.into())?;
                }
                Message::Notification(n) => {
                    if n.method == notif::Exit::METHOD {
                        return Ok(());
                    }
                    self.notification(n)?;
                }
                Message::Response(_) => {}
            }
            if self.conn.receiver.is_empty() {
                self.analyse_pending()?;
            }
        }
        Ok(())
    }

    /// Analyses every document edited since its last analysis and
    /// publishes its diagnostics with the version analysed.
    fn analyse_pending(&mut self) -> Result<()> {
        if self
            .docs
            .values()
            .all(|d| d.analysis.is_some() || d.crashed)
        {
            return Ok(());
        }
        // Includes of open documents read the editor's text, not the disk.
        let unsaved = self
            .docs
            .iter()
            .filter_map(|(uri, d)| {
                let path = uri.to_file_path().ok()?;
                Some((std::fs::canonicalize(&path).unwrap_or(path), d.text.clone()))
            })
            .collect();
        let opts = load::Options {
            unsaved: std::sync::Arc::new(unsaved),
            ..self.opts.clone()
        };
        for (uri, doc) in &mut self.docs {
            if doc.analysis.is_some() || doc.crashed {
                continue;
            }
            // A bug must not take the editor's server down: report it on
            // the document and keep serving the others.
            let analysed = panic::catch_unwind(AssertUnwindSafe(|| {
                let a = Analysis::new(uri, &doc.text, &opts);
                let d = diagnostics::diagnostics(&a);
                (a, d)
            }));
            let diagnostics = match analysed {
                Ok((a, d)) => {
                    doc.analysis = Some(a);
                    d
                }
                Err(_) => {
                    doc.analysis = None;
                    doc.crashed = true;
                    vec![Diagnostic {
                        severity: Some(DiagnosticSeverity::ERROR),
                        source: Some("lsys".into()),
                        message: "internal error: lsys could not analyse this file. This is a bug in lsys; please report it with the file".into(),
                        ..Diagnostic::default()
                    }]
                }
            };
            let params = PublishDiagnosticsParams {
                uri: uri.clone(),
                diagnostics,
                version: Some(doc.version),
            };
            self.conn
                .sender
                .send(Notification::new(notif::PublishDiagnostics::METHOD.into(), params).into())?;
        }
        self.stale.clear();
        Ok(())
    }

    fn notification(&mut self, n: Notification) -> Result<()> {
        match n.method.as_str() {
            notif::DidOpenTextDocument::METHOD => {
                let p: DidOpenTextDocumentParams = serde_json::from_value(n.params)?;
                self.docs.insert(
                    p.text_document.uri,
                    Document {
                        version: p.text_document.version,
                        text: p.text_document.text,
                        analysis: None,
                        crashed: false,
                    },
                );
            }
            notif::DidChangeTextDocument::METHOD => {
                let p: DidChangeTextDocumentParams = serde_json::from_value(n.params)?;
                if let Some(doc) = self.docs.get_mut(&p.text_document.uri) {
                    for change in p.content_changes {
                        apply(&mut doc.text, change);
                    }
                    doc.version = p.text_document.version;
                    doc.invalidate(&mut self.stale);
                    doc.crashed = false;
                }
                self.invalidate_readers(&p.text_document.uri);
            }
            notif::DidSaveTextDocument::METHOD => {
                // An included file may have changed on disk: analyse all again.
                for doc in self.docs.values_mut() {
                    doc.invalidate(&mut self.stale);
                    doc.crashed = false;
                }
            }
            notif::DidCloseTextDocument::METHOD => {
                let p: DidCloseTextDocumentParams = serde_json::from_value(n.params)?;
                self.docs.remove(&p.text_document.uri);
                self.invalidate_readers(&p.text_document.uri);
                let params = PublishDiagnosticsParams {
                    uri: p.text_document.uri,
                    diagnostics: Vec::new(),
                    version: None,
                };
                self.conn.sender.send(
                    Notification::new(notif::PublishDiagnostics::METHOD.into(), params).into(),
                )?;
            }
            _ => {}
        }
        Ok(())
    }

    /// Documents that include `uri` are analysed again (its text changed,
    /// or it was closed and the disk's text applies again).
    fn invalidate_readers(&mut self, uri: &Url) {
        for doc in self.docs.values_mut() {
            if doc.analysis.as_ref().is_some_and(|a| a.reads(uri)) {
                doc.invalidate(&mut self.stale);
            }
        }
    }

    fn request(&mut self, r: Request) -> Response {
        let id = r.id.clone();
        let answer = panic::catch_unwind(AssertUnwindSafe(|| self.answer(r)))
            .unwrap_or_else(|_| Err("internal error in lsys (a bug; please report it)".into()));
        match answer {
            Ok(v) => Response::new_ok(id, v),
            Err(e) => Response::new_err(id, lsp_server::ErrorCode::RequestFailed as i32, e),
        }
    }

    fn doc(&self, uri: &Url) -> std::result::Result<&Analysis, String> {
        self.docs
            .get(uri)
            .and_then(|d| d.analysis.as_ref())
            .ok_or_else(|| format!("{uri} is not open"))
    }

    fn answer(&self, r: Request) -> std::result::Result<Value, String> {
        fn params<P: serde::de::DeserializeOwned>(v: Value) -> std::result::Result<P, String> {
            serde_json::from_value(v).map_err(|e| format!("bad parameters: {e}"))
        }
        let json = Ok;
        match r.method.as_str() {
            req::HoverRequest::METHOD => {
                let p: HoverParams = params(r.params)?;
                let pos = p.text_document_position_params;
                let a = self.doc(&pos.text_document.uri)?;
                let occ = a.index.at(ROOT, navigate::offset(a, pos.position));
                let h = occ.and_then(|o| {
                    let text = hover::hover(a, o)?;
                    Some(Hover {
                        contents: HoverContents::Markup(MarkupContent {
                            kind: MarkupKind::Markdown,
                            value: text,
                        }),
                        range: navigate::location(a, o.span).map(|l| l.range),
                    })
                });
                json(to(&h))
            }
            req::GotoDefinition::METHOD => {
                let p: GotoDefinitionParams = params(r.params)?;
                let pos = p.text_document_position_params;
                let a = self.doc(&pos.text_document.uri)?;
                let locs = a
                    .index
                    .at(ROOT, navigate::offset(a, pos.position))
                    .map(|o| navigate::definition(a, o))
                    .unwrap_or_default();
                json(to(&GotoDefinitionResponse::Array(locs)))
            }
            req::References::METHOD => {
                let p: ReferenceParams = params(r.params)?;
                let pos = p.text_document_position;
                let a = self.doc(&pos.text_document.uri)?;
                let locs = a
                    .index
                    .at(ROOT, navigate::offset(a, pos.position))
                    .map(|o| navigate::references(a, o, p.context.include_declaration))
                    .unwrap_or_default();
                json(to(&locs))
            }
            req::PrepareRenameRequest::METHOD => {
                let p: TextDocumentPositionParams = params(r.params)?;
                let a = self.doc(&p.text_document.uri)?;
                let occ = a
                    .index
                    .at(ROOT, navigate::offset(a, p.position))
                    .ok_or("nothing to rename here")?;
                navigate::can_rename(a, occ)?;
                let range = navigate::location(a, occ.span).map(|l| l.range);
                json(to(&range.map(PrepareRenameResponse::Range)))
            }
            req::Rename::METHOD => {
                let p: RenameParams = params(r.params)?;
                let pos = p.text_document_position;
                let a = self.doc(&pos.text_document.uri)?;
                let occ = a
                    .index
                    .at(ROOT, navigate::offset(a, pos.position))
                    .ok_or("nothing to rename here")?;
                json(to(&navigate::rename(a, occ, &p.new_name)?))
            }
            req::Completion::METHOD => {
                let p: CompletionParams = params(r.params)?;
                let pos = p.text_document_position;
                let a = self.doc(&pos.text_document.uri)?;
                let offset = LineIndex::new(a.text(ROOT)).offset(pos.position);
                let trigger = p.context.and_then(|c| c.trigger_character);
                let items = complete::completions(a, offset, trigger.as_deref());
                json(to(&CompletionResponse::Array(items)))
            }
            req::SemanticTokensFullRequest::METHOD => {
                let p: SemanticTokensParams = params(r.params)?;
                let a = self.doc(&p.text_document.uri)?;
                json(to(&SemanticTokensResult::Tokens(SemanticTokens {
                    result_id: None,
                    data: complete::semantic_tokens(a),
                })))
            }
            req::DocumentSymbolRequest::METHOD => {
                let p: DocumentSymbolParams = params(r.params)?;
                let a = self.doc(&p.text_document.uri)?;
                json(to(&DocumentSymbolResponse::Nested(navigate::symbols(a))))
            }
            req::DocumentLinkRequest::METHOD => {
                let p: DocumentLinkParams = params(r.params)?;
                let a = self.doc(&p.text_document.uri)?;
                json(to(&navigate::links(a)))
            }
            req::CodeActionRequest::METHOD => {
                let p: CodeActionParams = params(r.params)?;
                json(to(&diagnostics::code_actions(
                    &p.text_document.uri,
                    &p.context.diagnostics,
                )))
            }
            req::InlayHintRequest::METHOD => {
                let p: InlayHintParams = params(r.params)?;
                let a = self.doc(&p.text_document.uri)?;
                json(to(&inlay::hints(a, p.range.start.line, p.range.end.line)))
            }
            req::CodeLensRequest::METHOD => {
                let p: CodeLensParams = params(r.params)?;
                let a = self.doc(&p.text_document.uri)?;
                json(to(a.lenses.get_or_init(|| lens::lenses(a))))
            }
            other => Err(format!("lsys lsp does not answer {other}")),
        }
    }
}

/// A result as JSON.
fn to<T: serde::Serialize>(v: &T) -> Value {
    serde_json::to_value(v).unwrap_or(Value::Null)
}

/// Applies one change to a document's text (a range replacement, or the
/// whole text when the change has no range).
fn apply(text: &mut String, change: TextDocumentContentChangeEvent) {
    match change.range {
        Some(range) => {
            let ix = LineIndex::new(text);
            let (s, e) = (ix.offset(range.start), ix.offset(range.end));
            let e = e.max(s);
            text.replace_range(s..e, &change.text);
        }
        None => *text = change.text,
    }
}
