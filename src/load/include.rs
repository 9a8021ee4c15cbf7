//! Load: finding and reading the files a model names. An include name and
//! the including file's folder in; the file's path and text out, or why it
//! cannot be used. The one finder for `.lsys` includes, the C
//! preprocessor's includes of cpfg files and the view file's function
//! files: the same search order, the same folder confinement, the same size
//! and NUL checks.

use std::path::{Path, PathBuf};

/// Larger files are not grammars (a log, a disk image): refused unread
/// rather than loaded whole into memory.
pub const MAX_SOURCE_BYTES: u64 = 64 << 20;

/// Why a source file was not read.
pub(super) enum Unread {
    /// It could not be read (missing, a folder, no permission).
    Io(std::io::Error),
    /// It is not an L-system source: why.
    NotSource(String),
}

impl From<std::io::Error> for Unread {
    fn from(e: std::io::Error) -> Unread {
        Unread::Io(e)
    }
}

/// Reads a source file's bytes, refusing files too large or binary. The
/// top-level grammar may be a pipe or a device (`lsys check /dev/stdin`):
/// it is read up to the limit and refused past it, never read whole into
/// memory. An included file (`only_regular`) must be a regular file: a
/// named pipe would wait for a writer forever, a device never end.
pub(super) fn read_source(path: &Path, only_regular: bool) -> Result<Vec<u8>, Unread> {
    use std::io::Read;
    // Asked before opening: opening a named pipe waits for its writer.
    let meta = std::fs::metadata(path)?;
    let len = meta.len();
    if meta.is_file() && len > MAX_SOURCE_BYTES {
        return Err(Unread::NotSource(format!(
            "it is {len} bytes long, more than the {} MiB a grammar file may have",
            MAX_SOURCE_BYTES >> 20
        )));
    }
    if only_regular && !meta.is_file() && !meta.is_dir() {
        return Err(Unread::NotSource(format!(
            "it is {}, not a regular file; copy its text into a file",
            kind_of(&meta)
        )));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(MAX_SOURCE_BYTES + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_SOURCE_BYTES {
        return Err(Unread::NotSource(format!(
            "it holds more than the {} MiB a grammar file may have",
            MAX_SOURCE_BYTES >> 20
        )));
    }
    if is_binary(&bytes) {
        return Err(Unread::NotSource(
            "it holds NUL bytes, as binary and UTF-16 files do".to_string(),
        ));
    }
    Ok(bytes)
}

/// What a file that is not a regular file or a folder is, for messages.
fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a named pipe";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    let _ = meta;
    "a special file"
}

/// Text files never hold NUL bytes; binary and UTF-16 files do. Such a
/// file is refused unread, so that no diagnostic shows its bytes. (Other
/// invalid UTF-8, e.g. Latin-1 comments in old cpfg files, is read lossily.)
fn is_binary(bytes: &[u8]) -> bool {
    bytes.contains(&0)
}

/// Why a named file cannot be used; `full` is where lsys looked.
#[derive(Debug)]
pub(super) enum Refused {
    /// It resolves (links followed) outside every allowed folder; `help`
    /// names the file and the folders.
    Outside { help: String },
    /// Too large, or binary.
    NotSource { full: PathBuf, why: String },
    /// Missing or unreadable.
    NotFound { full: PathBuf, cause: String },
}

/// Where included files are searched and which folders they must stay in.
#[derive(Clone, Debug)]
pub(super) struct IncludeFinder {
    /// Every file read must resolve (links followed) inside one of these:
    /// the top-level file's folder, then the `--include-dir`s.
    roots: Vec<PathBuf>,
    /// The same folders as the user named them, for messages.
    roots_shown: Vec<PathBuf>,
    /// `--include-dir`: searched after the including file's folder.
    include_dirs: Vec<PathBuf>,
    /// Unsaved texts by canonical path (see `Options::unsaved`).
    unsaved: std::sync::Arc<std::collections::HashMap<PathBuf, String>>,
}

impl IncludeFinder {
    /// Includes stay inside `root_dir` (the top-level file's folder, or the
    /// working folder for text and library grammars) and the
    /// `--include-dir`s: a grammar from someone else cannot read
    /// ../../etc/passwd, nor show its lines in a diagnostic.
    pub(super) fn new(
        root_dir: PathBuf,
        include_dirs: &[PathBuf],
        unsaved: std::sync::Arc<std::collections::HashMap<PathBuf, String>>,
    ) -> IncludeFinder {
        // A missing `--include-dir` allows nothing: it cannot be
        // canonicalised, so nothing starts with it.
        let mut roots = vec![std::fs::canonicalize(&root_dir).unwrap_or_else(|_| root_dir.clone())];
        roots.extend(
            include_dirs
                .iter()
                .filter_map(|d| std::fs::canonicalize(d).ok()),
        );
        let mut roots_shown = vec![root_dir];
        roots_shown.extend(include_dirs.iter().cloned());
        IncludeFinder {
            roots,
            roots_shown,
            include_dirs: include_dirs.to_vec(),
            unsaved,
        }
    }

    /// The file `name` included from a file in `base`: beside it, else in
    /// the first `--include-dir` that has it. Its path and text (invalid
    /// UTF-8 read lossily).
    pub(super) fn find(&self, base: &Path, name: &str) -> Result<(PathBuf, String), Refused> {
        let mut full = base.join(name);
        if !full.exists() {
            if let Some(found) = self
                .include_dirs
                .iter()
                .map(|d| d.join(name))
                .find(|p| p.exists())
            {
                full = found;
            }
        }
        let text = self.read(&full)?;
        Ok((full, text))
    }

    /// Reads the binary file at `full` (an environment's input image) if
    /// it is inside the allowed folders and at most [`MAX_SOURCE_BYTES`].
    pub(super) fn read_bytes(&self, full: &Path) -> Result<Vec<u8>, Refused> {
        self.confined(full)?;
        let cause = |e: std::io::Error| Refused::NotFound {
            full: full.to_path_buf(),
            cause: e.to_string(),
        };
        let meta = std::fs::metadata(full).map_err(cause)?;
        if !meta.is_file() && !meta.is_dir() {
            return Err(Refused::NotSource {
                full: full.to_path_buf(),
                why: format!("it is {}, not a regular file", kind_of(&meta)),
            });
        }
        let len = meta.len();
        if len > MAX_SOURCE_BYTES {
            return Err(Refused::NotSource {
                full: full.to_path_buf(),
                why: format!(
                    "it is {len} bytes long, more than the {} MiB lsys reads",
                    MAX_SOURCE_BYTES >> 20
                ),
            });
        }
        std::fs::read(full).map_err(cause)
    }

    /// Reads the file at `full` if it is inside the allowed folders and is
    /// a text file of at most [`MAX_SOURCE_BYTES`].
    /// An editor's unsaved text of the file wins over the disk's.
    pub(super) fn read(&self, full: &Path) -> Result<String, Refused> {
        self.confined(full)?;
        if let Ok(real) = std::fs::canonicalize(full) {
            if let Some(text) = self.unsaved.get(&real) {
                return Ok(text.clone());
            }
        }
        self.read_text(full)
    }

    /// `Err` when `full` resolves (links followed) outside the allowed
    /// folders.
    fn confined(&self, full: &Path) -> Result<(), Refused> {
        if let Ok(real) = std::fs::canonicalize(full) {
            // `real` is only compared, never shown: messages keep the
            // user's own relative paths.
            if !self.roots.iter().any(|r| real.starts_with(r)) {
                let inside = self
                    .roots_shown
                    .iter()
                    .map(|d| d.display().to_string())
                    .collect::<Vec<_>>()
                    .join(" or ");
                return Err(Refused::Outside {
                    help: format!(
                        "{} is not inside {inside} (links are followed); copy the file into that folder or below it, or allow its folder with `--include-dir DIR`",
                        full.display(),
                    ),
                });
            }
        }
        Ok(())
    }

    fn read_text(&self, full: &Path) -> Result<String, Refused> {
        match read_source(full, true) {
            Ok(bytes) => Ok(String::from_utf8_lossy(&bytes).into_owned()),
            Err(Unread::NotSource(why)) => Err(Refused::NotSource {
                full: full.to_path_buf(),
                why,
            }),
            Err(Unread::Io(e)) => Err(Refused::NotFound {
                full: full.to_path_buf(),
                cause: e.to_string(),
            }),
        }
    }
}

impl Refused {
    /// One line for messages that have no structure of their own (the
    /// preprocessor's, the view file's).
    pub(super) fn message(&self) -> String {
        match self {
            Refused::Outside { help, .. } => help.clone(),
            Refused::NotSource { full, why } => {
                format!("{} is not an L-system source: {why}", full.display())
            }
            Refused::NotFound { full, cause } => format!("cannot read {}: {cause}", full.display()),
        }
    }
}
