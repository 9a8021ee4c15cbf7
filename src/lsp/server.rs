//! The server's main loop. Input: messages from an
//! [`lsp_server::Connection`]; output: responses and notifications on it.
//! The loop owns the state (open documents: text, version, last finished
//! analysis) and applies document edits in arrival order. Once no message
//! is waiting it starts an analysis of each changed document on a worker
//! thread (one at a time per document; the result of a text edited since
//! is kept for requests but its diagnostics are not published), gives up
//! an analysis that runs past [`ANALYSIS_BUDGET`], and answers each
//! request at once from the last finished analysis of its document (a
//! document's very first analysis is waited for, within the budget).

use std::collections::BTreeMap;
use std::error::Error;
use std::panic::{self, AssertUnwindSafe};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use lsp_server::{Connection, ErrorCode, Message, Notification, Request, Response};
use lsp_types::notification::{self as notif, Notification as _};
use lsp_types::request::{self as req, Request as _};
use lsp_types::*;
use serde_json::Value;

use super::analysis::{Analysis, ROOT};
use super::position::LineIndex;
use super::{complete, diagnostics, hover, inlay, lens, navigate};
use crate::load;

type Result<T> = std::result::Result<T, Box<dyn Error + Send + Sync>>;

/// Documents larger than this (in bytes) are not analysed: the server
/// publishes one "too large" diagnostic instead and answers requests on
/// them with nothing (docs/editors.md, "Limits"). Analysing costs about
/// 1 s per MB here, and the editor waits for diagnostics after each change.
pub const MAX_ANALYSED: usize = 1 << 20;

/// The wall-clock budget of one analysis. A slower analysis is given up:
/// its document gets a diagnostic saying so, the thread is left to finish
/// (or hit the compiler's own limits) and its result is dropped, and the
/// next edit starts a fresh analysis. `LSYS_LSP_BUDGET_MS` overrides it
/// (the tests use a short one).
pub const ANALYSIS_BUDGET: Duration = Duration::from_secs(10);

fn budget() -> Duration {
    std::env::var("LSYS_LSP_BUDGET_MS")
        .ok()
        .and_then(|v| v.parse().ok())
        .map_or(ANALYSIS_BUDGET, Duration::from_millis)
}

struct Document {
    version: i32,
    text: String,
    /// Counts edits: an analysis result is current when its generation
    /// is the document's.
    generation: u64,
    /// The last finished analysis and its generation (possibly of an
    /// older text: requests are answered from it rather than waiting).
    analysis: Option<(u64, Analysis)>,
    /// The generation whose diagnostics were published (an analysis, a
    /// crash, a "too large" or "too slow" notice): nothing to do until
    /// the next edit.
    published: Option<u64>,
    /// The generation being analysed and when it started.
    running: Option<(u64, Instant)>,
}

/// What the loop waits for: a message from the client, or an analysis
/// finished on its worker thread.
enum Event {
    Message(Message),
    /// Boxed: an analysis is large and the channel holds mostly messages.
    Analysed(Box<Analysed>),
    Closed,
}

struct Analysed {
    uri: Url,
    generation: u64,
    /// `Err` when analysing panicked (a bug).
    outcome: std::thread::Result<(Analysis, Vec<Diagnostic>)>,
}

struct Server<'c> {
    conn: &'c Connection,
    opts: load::Options,
    docs: BTreeMap<Url, Document>,
    events: mpsc::Sender<Event>,
    /// Requests on a document that has no analysis yet, answered when
    /// its first one finishes (or fails, or runs out of budget).
    waiting: Vec<Request>,
    budget: Duration,
}

impl Document {
    fn edited(&mut self) {
        self.generation += 1;
    }

    fn current(&self) -> bool {
        self.published == Some(self.generation)
    }
}

/// A request failure: the JSON-RPC error code and message.
struct Failure(i32, String);

impl From<String> for Failure {
    fn from(m: String) -> Failure {
        Failure(ErrorCode::RequestFailed as i32, m)
    }
}

impl From<&str> for Failure {
    fn from(m: &str) -> Failure {
        Failure(ErrorCode::RequestFailed as i32, m.to_string())
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
/// until `shutdown` and `exit` (or the client closing the connection).
pub fn serve(conn: Connection, opts: load::Options) -> Result<()> {
    let (id, _params) = conn.initialize_start()?;
    let result = InitializeResult {
        capabilities: capabilities(),
        server_info: Some(ServerInfo {
            name: "lsys".into(),
            version: Some(env!("CARGO_PKG_VERSION").into()),
        }),
    };
    // Not `initialize_finish`: it ends the server when the next message
    // is anything but `initialized`; the loop ignores `initialized`.
    conn.sender
        .send(Response::new_ok(id, serde_json::to_value(result)?).into())?;
    let (events, incoming) = mpsc::channel();
    // The client's messages and the workers' results arrive on one channel.
    let forward = events.clone();
    let receiver = conn.receiver.clone();
    std::thread::Builder::new()
        .name("lsp-forward".into())
        .spawn(move || {
            for m in receiver {
                if forward.send(Event::Message(m)).is_err() {
                    return;
                }
            }
            let _ = forward.send(Event::Closed);
        })?;
    let mut server = Server {
        conn: &conn,
        opts,
        docs: BTreeMap::new(),
        events,
        waiting: Vec::new(),
        budget: budget(),
    };
    server.run(incoming)
}

impl Server<'_> {
    fn run(&mut self, incoming: mpsc::Receiver<Event>) -> Result<()> {
        let mut shut_down = false;
        let mut next: Option<Event> = None;
        loop {
            let event = match next.take() {
                Some(e) => e,
                None => match self.deadline() {
                    Some(d) => match incoming.recv_timeout(d) {
                        Ok(e) => e,
                        Err(mpsc::RecvTimeoutError::Timeout) => {
                            self.over_budget()?;
                            continue;
                        }
                        Err(mpsc::RecvTimeoutError::Disconnected) => return Ok(()),
                    },
                    None => incoming.recv().unwrap_or(Event::Closed),
                },
            };
            match event {
                Event::Closed => return Ok(()),
                Event::Analysed(a) => self.finished(*a)?,
                Event::Message(Message::Request(r)) => {
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
                            ErrorCode::InvalidRequest as i32,
                            "the server is shutting down".into(),
                        );
                        self.conn.sender.send(e.into())?;
                        continue;
                    }
                    if self.must_wait(&r) {
                        self.waiting.push(r);
                    } else {
                        let response = self.request(r);
                        self.conn.sender.send(response.into())?;
                    }
                }
                Event::Message(Message::Notification(n)) => {
                    if n.method == notif::Exit::METHOD {
                        return Ok(());
                    }
                    self.notification(n)?;
                }
                Event::Message(Message::Response(_)) => {}
            }
            self.over_budget()?;
            // A burst of edits is analysed once: only when nothing waits.
            match incoming.try_recv() {
                Ok(e) => next = Some(e),
                Err(_) => self.start_pending()?,
            }
        }
    }

    /// How long until the oldest running analysis runs out of budget.
    fn deadline(&self) -> Option<Duration> {
        self.docs
            .values()
            .filter_map(|d| d.running)
            .map(|(_, t)| (t + self.budget).saturating_duration_since(Instant::now()))
            .min()
    }

    /// A request on a document being analysed for the first time waits
    /// for that analysis; every other request is answered at once.
    fn must_wait(&self, r: &Request) -> bool {
        let Some(uri) = request_uri(r) else {
            return false;
        };
        self.docs
            .get(&uri)
            .is_some_and(|d| d.analysis.is_none() && !d.current())
    }

    /// Answers the waiting requests that need not wait any more.
    fn answer_waiting(&mut self) -> Result<()> {
        let waiting = std::mem::take(&mut self.waiting);
        for r in waiting {
            if self.must_wait(&r) {
                self.waiting.push(r);
            } else {
                let response = self.request(r);
                self.conn.sender.send(response.into())?;
            }
        }
        Ok(())
    }

    fn publish(&self, uri: &Url, version: Option<i32>, diagnostics: Vec<Diagnostic>) -> Result<()> {
        let params = PublishDiagnosticsParams {
            uri: uri.clone(),
            diagnostics,
            version,
        };
        self.conn
            .sender
            .send(Notification::new(notif::PublishDiagnostics::METHOD.into(), params).into())?;
        Ok(())
    }

    /// Starts an analysis of every document edited since its last one
    /// that has none running (an edit during a running analysis waits for
    /// it to finish or run out of budget: one worker per document).
    fn start_pending(&mut self) -> Result<()> {
        let pending: Vec<Url> = self
            .docs
            .iter()
            .filter(|(_, d)| !d.current() && d.running.is_none())
            .map(|(u, _)| u.clone())
            .collect();
        if pending.is_empty() {
            return Ok(());
        }
        // Includes of open documents read the editor's text, not the disk.
        let unsaved: std::collections::HashMap<_, _> = self
            .docs
            .iter()
            .filter(|(_, d)| d.text.len() <= MAX_ANALYSED)
            .filter_map(|(uri, d)| {
                let path = uri.to_file_path().ok()?;
                Some((std::fs::canonicalize(&path).unwrap_or(path), d.text.clone()))
            })
            .collect();
        let opts = load::Options {
            unsaved: std::sync::Arc::new(unsaved.into_iter().collect()),
            ..self.opts.clone()
        };
        for uri in pending {
            let doc = self.docs.get_mut(&uri).expect("listed above");
            if doc.text.len() > MAX_ANALYSED {
                // Degraded: no analysis, requests answer nothing.
                doc.analysis = None;
                doc.published = Some(doc.generation);
                let message = format!(
                    "this file is too large for the language server ({:.1} MB; the limit is {} MB): no diagnostics, hovers or completions. `lsys check` checks it.",
                    doc.text.len() as f64 / 1e6,
                    MAX_ANALYSED >> 20
                );
                let d = Diagnostic {
                    severity: Some(DiagnosticSeverity::WARNING),
                    source: Some("lsys".into()),
                    code: Some(NumberOrString::String("lsys::lsp::too_large".into())),
                    message,
                    ..Diagnostic::default()
                };
                let version = doc.version;
                self.publish(&uri, Some(version), vec![d])?;
                continue;
            }
            let generation = doc.generation;
            doc.running = Some((generation, Instant::now()));
            let text = doc.text.clone();
            let events = self.events.clone();
            let opts = opts.clone();
            let job_uri = uri.clone();
            let spawned = std::thread::Builder::new()
                .name("lsp-analysis".into())
                .stack_size(crate::build::WORKER_STACK)
                .spawn(move || {
                    // A bug must not take the editor's server down: the
                    // panic is reported on the document.
                    let outcome = panic::catch_unwind(AssertUnwindSafe(|| {
                        let a = Analysis::new(&job_uri, &text, &opts);
                        let d = diagnostics::diagnostics(&a);
                        (a, d)
                    }));
                    let _ = events.send(Event::Analysed(Box::new(Analysed {
                        uri: job_uri,
                        generation,
                        outcome,
                    })));
                });
            if let Err(e) = spawned {
                eprintln!("lsys lsp: cannot start an analysis: {e}");
                doc.running = None;
                doc.published = Some(generation);
            }
        }
        Ok(())
    }

    /// Takes in a finished analysis: kept if newer than the document's,
    /// its diagnostics published only if its text is still current.
    fn finished(&mut self, done: Analysed) -> Result<()> {
        let Some(doc) = self.docs.get_mut(&done.uri) else {
            return Ok(()); // closed meanwhile
        };
        if doc.running.is_some_and(|(g, _)| g == done.generation) {
            doc.running = None;
        }
        let current = done.generation == doc.generation && !doc.current();
        // The replaced analysis is freed after the diagnostics are sent:
        // freeing a large model takes milliseconds the editor need not wait.
        let mut old = None;
        let diagnostics = match done.outcome {
            Ok((a, d)) => {
                if doc.analysis.as_ref().map_or(true, |(g, _)| *g < done.generation) {
                    old = doc.analysis.replace((done.generation, a));
                }
                d
            }
            Err(_) => vec![Diagnostic {
                severity: Some(DiagnosticSeverity::ERROR),
                source: Some("lsys".into()),
                message: "internal error: lsys could not analyse this file. This is a bug in lsys; please report it with the file".into(),
                ..Diagnostic::default()
            }],
        };
        if current {
            doc.published = Some(done.generation);
            let version = doc.version;
            self.publish(&done.uri, Some(version), diagnostics)?;
        }
        drop(old);
        self.answer_waiting()
    }

    /// Gives up the analyses that ran past the budget (see
    /// [`ANALYSIS_BUDGET`]).
    fn over_budget(&mut self) -> Result<()> {
        let now = Instant::now();
        let mut late = Vec::new();
        for (uri, doc) in &mut self.docs {
            let Some((g, t)) = doc.running else { continue };
            if now < t + self.budget {
                continue;
            }
            doc.running = None;
            if g == doc.generation {
                doc.published = Some(g);
                late.push((uri.clone(), doc.version));
            }
        }
        if late.is_empty() {
            return Ok(());
        }
        for (uri, version) in late {
            let d = Diagnostic {
                severity: Some(DiagnosticSeverity::ERROR),
                source: Some("lsys".into()),
                code: Some(NumberOrString::String("lsys::lsp::too_slow".into())),
                message: format!(
                    "lsys gave up analysing this file after {:.1} s (the language server's budget): hovers and completions use the last analysis that finished. `lsys check` shows where the time goes.",
                    self.budget.as_secs_f64()
                ),
                ..Diagnostic::default()
            };
            self.publish(&uri, Some(version), vec![d])?;
        }
        self.answer_waiting()
    }

    fn notification(&mut self, n: Notification) -> Result<()> {
        fn params<P: serde::de::DeserializeOwned>(n: Notification) -> Option<P> {
            match serde_json::from_value(n.params) {
                Ok(p) => Some(p),
                Err(e) => {
                    // A notification has no answer: say it and go on.
                    eprintln!("lsys lsp: {} with bad parameters ({e}): ignored", n.method);
                    None
                }
            }
        }
        match n.method.as_str() {
            notif::DidOpenTextDocument::METHOD => {
                let Some(p) = params::<DidOpenTextDocumentParams>(n) else {
                    return Ok(());
                };
                let old = self.docs.remove(&p.text_document.uri);
                self.docs.insert(
                    p.text_document.uri.clone(),
                    Document {
                        version: p.text_document.version,
                        text: p.text_document.text,
                        generation: old.as_ref().map_or(0, |d| d.generation + 1),
                        analysis: None,
                        published: None,
                        running: old.and_then(|d| d.running),
                    },
                );
            }
            notif::DidChangeTextDocument::METHOD => {
                let Some(p) = params::<DidChangeTextDocumentParams>(n) else {
                    return Ok(());
                };
                if let Some(doc) = self.docs.get_mut(&p.text_document.uri) {
                    for change in p.content_changes {
                        apply(&mut doc.text, change);
                    }
                    doc.version = p.text_document.version;
                    doc.edited();
                }
                self.invalidate_readers(&p.text_document.uri);
            }
            notif::DidSaveTextDocument::METHOD => {
                // An included file may have changed on disk: analyse all again.
                for doc in self.docs.values_mut() {
                    doc.edited();
                }
            }
            notif::DidCloseTextDocument::METHOD => {
                let Some(p) = params::<DidCloseTextDocumentParams>(n) else {
                    return Ok(());
                };
                self.docs.remove(&p.text_document.uri);
                self.invalidate_readers(&p.text_document.uri);
                self.publish(&p.text_document.uri, None, Vec::new())?;
                self.answer_waiting()?;
            }
            _ => {}
        }
        Ok(())
    }

    /// Documents that include `uri` are analysed again (its text changed,
    /// or it was closed and the disk's text applies again).
    fn invalidate_readers(&mut self, uri: &Url) {
        for (u, doc) in &mut self.docs {
            if u != uri && doc.analysis.as_ref().is_some_and(|(_, a)| a.reads(uri)) {
                doc.edited();
            }
        }
    }

    fn request(&mut self, r: Request) -> Response {
        let id = r.id.clone();
        let answer = panic::catch_unwind(AssertUnwindSafe(|| self.answer(r)))
            .unwrap_or_else(|_| Err("internal error in lsys (a bug; please report it)".into()));
        match answer {
            Ok(v) => Response::new_ok(id, v),
            Err(Failure(code, e)) => Response::new_err(id, code, e),
        }
    }

    fn doc(&self, uri: &Url) -> std::result::Result<&Analysis, String> {
        self.docs
            .get(uri)
            .and_then(|d| d.analysis.as_ref())
            .map(|(_, a)| a)
            .ok_or_else(|| match self.docs.get(uri) {
                Some(_) => format!("{uri} is not analysed (too large or too slow)"),
                None => format!("{uri} is not open"),
            })
    }

    fn answer(&self, r: Request) -> std::result::Result<Value, Failure> {
        fn params<P: serde::de::DeserializeOwned>(v: Value) -> std::result::Result<P, Failure> {
            serde_json::from_value(v).map_err(|e| {
                Failure(
                    ErrorCode::InvalidParams as i32,
                    format!("bad parameters: {e}"),
                )
            })
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
            other => Err(Failure(
                ErrorCode::MethodNotFound as i32,
                format!("lsys lsp does not answer {other}"),
            )),
        }
    }
}

/// The document a request is about (`textDocument.uri` in its parameters).
fn request_uri(r: &Request) -> Option<Url> {
    Url::parse(r.params.pointer("/textDocument/uri")?.as_str()?).ok()
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
