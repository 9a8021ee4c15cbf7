//! `lsys studio`: a local web server for the Pailou editor and the live
//! grammar preview. Input: a folder (and optionally a `.lsys` or graph
//! `.toml` in it) and an address; output: the page, a JSON API and GLB
//! models over HTTP, updates pushed as server-sent events. In grammar mode
//! a save of a file the grammar read rebuilds the model: the driver's file
//! watcher ([`crate::driver::Watcher`], the one `lsys watch` uses), told
//! the files by every build before it reads them.
//!
//! The server is synchronous (tiny_http, one thread per request) like the
//! rest of the crate. It binds to loopback unless told otherwise, answers
//! only requests whose `Host`/`Origin` is its own, reads and writes only
//! inside the opened folder, limits request bodies, and never lets a bad
//! graph or grammar take it down (docs/studio.md). The drawing page
//! (`drawing.rs`, its routes in `drawing_routes.rs`) reads elevation
//! drawings into shape grammars beside whichever session is open; the
//! guides page (`guides.rs`, `guides_routes.rs`) edits guided scenes; the
//! painting page (`painting.rs`, `painting_routes.rs`) paints parts in
//! five views into a `.lsys` session of construction rules.

mod drawing;
mod drawing_routes;
mod grammar;
mod guides;
mod guides_routes;
mod http;
mod listing;
mod model;
mod pailou;
mod painting;
mod painting_routes;
mod reply;
mod safety;

use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::Duration;

use crate::driver::{Change, Watcher};

pub use grammar::{defines_of, Define, GrammarSession};
pub use http::has_embedded_page;
pub use model::{Model, DEFAULT_MAX_TRIANGLES};
pub use pailou::{PailouSession, DEFAULT_ENTRANCE};
pub use safety::{confine, ConfineError};

/// What to open and where to listen.
#[derive(Clone, Debug)]
pub struct Config {
    /// A `.lsys` file, a graph `.toml` or a folder; `None`: the current
    /// folder with the default entrance.
    pub path: Option<PathBuf>,
    /// The address to bind (loopback unless the user says otherwise).
    pub bind: std::net::IpAddr,
    /// 0 picks a free port.
    pub port: u16,
    /// The built front end (`web/studio/dist`); `None` looks next to the
    /// crate's sources, and without one the server's own page says how to
    /// build it.
    pub assets: Option<PathBuf>,
    /// Triangles a model may have (instances counted in full); `None`:
    /// [`model::DEFAULT_MAX_TRIANGLES`].
    pub max_triangles: Option<usize>,
}

/// A running studio.
pub struct Handle {
    pub addr: SocketAddr,
    server: Arc<tiny_http::Server>,
    shared: Arc<Shared>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Handle {
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// Stops accepting requests and waits for the accept loop to end.
    pub fn stop(mut self) {
        self.shutdown();
    }

    /// Blocks until the server stops (Ctrl-C ends the process).
    pub fn wait(mut self) {
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }

    fn shutdown(&mut self) {
        *lock(&self.shared.stopped) = true;
        self.shared.changed.notify_all();
        self.server.unblock();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for Handle {
    fn drop(&mut self) {
        if self.thread.is_some() {
            self.shutdown();
        }
    }
}

// A studio holds one session at a time, so the variants' sizes (a Pailou
// session's graph, chart and maps against a grammar session's) cost
// nothing worth a box.
#[allow(clippy::large_enum_variant)]
pub(crate) enum Session {
    Pailou(pailou::PailouSession),
    Grammar(grammar::GrammarSession),
}

/// What every request thread shares.
pub(crate) struct Shared {
    /// The opened folder, canonical.
    pub root: PathBuf,
    pub assets: Option<PathBuf>,
    /// `host:port` values the server answers to.
    pub hosts: Vec<String>,
    pub session: Mutex<Session>,
    /// The drawing page's drawing (`None` until one is opened); apart from
    /// `session`, so that both pages work at once.
    pub drawing: Mutex<Option<drawing::DrawingSession>>,
    /// The guides page's scene (`None` until one is opened).
    pub guides: Mutex<Option<guides::GuideSession>>,
    /// The painting page's session (`None` until one is opened).
    pub painting: Mutex<Option<painting::PaintSession>>,
    /// Bumped on every change of the model; waited on by event streams.
    pub version: Mutex<u64>,
    pub changed: Condvar,
    pub stopped: Mutex<bool>,
    /// The triangle budget of every model built.
    pub max_triangles: usize,
    /// Grammar mode's watcher (`None`: the system's could not be made;
    /// saves then wait for the page's next change).
    pub watcher: Option<Arc<Watcher>>,
}

impl Shared {
    pub fn bump(&self) {
        *lock(&self.version) += 1;
        self.changed.notify_all();
    }
}

/// A lock that survives a panic in another request (the session's data
/// is replaced whole on success, so it is never half-updated).
pub(crate) fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// The front end's build, next to the crate's sources.
pub fn default_assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("web/studio/dist")
}

/// Opens `config.path` and starts serving; returns once listening.
pub fn start(config: Config) -> Result<Handle, String> {
    let budget = config.max_triangles.unwrap_or(model::DEFAULT_MAX_TRIANGLES);
    // Made before the first session reads its grammar: a save right after
    // opening is its first change.
    let watcher = match Watcher::new() {
        Ok(w) => Some(Arc::new(w)),
        Err(e) => {
            eprintln!("lsys: {e}; the page will not follow saves");
            None
        }
    };
    let (root, session) = open_path(config.path.as_deref(), watcher.as_ref(), budget)?;
    let server = tiny_http::Server::http(SocketAddr::new(config.bind, config.port))
        .map_err(|e| format!("cannot listen on {}:{}: {e}", config.bind, config.port))?;
    let addr = server
        .server_addr()
        .to_ip()
        .ok_or("the server has no IP address")?;
    let port = addr.port();
    let mut hosts = vec![
        format!("127.0.0.1:{port}"),
        format!("localhost:{port}"),
        format!("[::1]:{port}"),
    ];
    hosts.push(match addr.ip() {
        std::net::IpAddr::V6(ip) => format!("[{ip}]:{port}"),
        ip => format!("{ip}:{port}"),
    });
    // `--assets`, else the build beside the sources (a developer's
    // checkout, rebuilt after the binary), else the one built into the
    // binary (`None` here).
    let assets = config
        .assets
        .or_else(|| Some(default_assets()))
        .filter(|a| a.join("index.html").is_file());
    let shared = Arc::new(Shared {
        root,
        assets,
        hosts,
        session: Mutex::new(session),
        drawing: Mutex::new(None),
        guides: Mutex::new(None),
        painting: Mutex::new(None),
        max_triangles: budget,
        version: Mutex::new(1),
        changed: Condvar::new(),
        stopped: Mutex::new(false),
        watcher,
    });
    let server = Arc::new(server);
    if let Some(w) = shared.watcher.clone() {
        let sh = shared.clone();
        std::thread::Builder::new()
            .name("studio-watch".into())
            .stack_size(crate::driver::WORKER_STACK)
            .spawn(move || watch(&sh, &w))
            .map_err(|e| e.to_string())?;
    }
    let (s, sh) = (server.clone(), shared.clone());
    let thread = std::thread::Builder::new()
        .name("studio-accept".into())
        .spawn(move || http::serve(&s, &sh))
        .map_err(|e| e.to_string())?;
    Ok(Handle {
        addr,
        server,
        shared,
        thread: Some(thread),
    })
}

/// The folder and first session for a path from the command line.
fn open_path(
    path: Option<&Path>,
    watcher: Option<&Arc<Watcher>>,
    budget: usize,
) -> Result<(PathBuf, Session), String> {
    let path = path.unwrap_or(Path::new("."));
    let full = path
        .canonicalize()
        .map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    if full.is_dir() {
        let session = Session::Pailou(pailou::PailouSession::open(
            "default entrance",
            DEFAULT_ENTRANCE,
            None,
            budget,
        ));
        return Ok((full, session));
    }
    let root = full
        .parent()
        .ok_or_else(|| format!("{} has no folder", path.display()))?
        .to_path_buf();
    let name = full
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    Ok((root.clone(), open_file(&root, &name, watcher, budget)?))
}

/// A session for `rel` (a graph `.toml` or a grammar), inside `root`; a
/// grammar tells `watcher` its files.
pub(crate) fn open_file(
    root: &Path,
    rel: &str,
    watcher: Option<&Arc<Watcher>>,
    budget: usize,
) -> Result<Session, String> {
    let full = confine(root, rel).map_err(|e| e.to_string())?;
    if rel.ends_with(".toml") {
        let text = std::fs::read_to_string(&full).map_err(|e| format!("cannot read {rel}: {e}"))?;
        match crate::driver::toml_file(Path::new(rel), &text) {
            Ok(crate::driver::TomlFile::PailouGraph) => {}
            Ok(crate::driver::TomlFile::GuidedScene) => {
                return Err(format!(
                    "{rel} is a guided scene (docs/guided.md), not a Pailou graph; the studio edits graphs and grammars: build the scene with `lsys build {rel} -o OUT.glb`"
                ))
            }
            Err(e) => {
                use miette::Diagnostic;
                let help = e.help().map(|h| h.to_string()).unwrap_or_default();
                return Err(format!("{e}; {help}"));
            }
        }
        // Pailou mode follows no files.
        if let Some(w) = watcher {
            let _ = w.watch_files(&[]);
        }
        Ok(Session::Pailou(pailou::PailouSession::open(
            rel,
            &text,
            Some(rel.to_string()),
            budget,
        )))
    } else if full.is_file() {
        Ok(Session::Grammar(grammar::GrammarSession::open_watched(
            root.to_path_buf(),
            full,
            rel.to_string(),
            watcher.cloned(),
            budget,
        )))
    } else {
        Err(format!(
            "{rel} is neither a graph (.toml) nor a grammar file"
        ))
    }
}

/// Grammar mode's watcher thread: rebuilds when one of the files the
/// grammar session gave `watcher` changes (it gives them before each
/// build reads them, so a save during a build is the next change). Looks
/// whether the server stopped every [`STOP_CHECK`].
fn watch(shared: &Shared, watcher: &Watcher) {
    loop {
        let change = watcher.wait_for_change(Some(STOP_CHECK));
        if *lock(&shared.stopped) {
            return;
        }
        match change {
            Change::Changed => {}
            Change::TimedOut => continue,
            Change::Closed => return,
        }
        let rebuilt = match &mut *lock(&shared.session) {
            Session::Grammar(g) => {
                g.rebuild();
                true
            }
            _ => false,
        };
        if rebuilt {
            shared.bump();
        }
    }
}

/// How long the watcher thread waits before it looks whether the server
/// stopped.
const STOP_CHECK: Duration = Duration::from_millis(150);
