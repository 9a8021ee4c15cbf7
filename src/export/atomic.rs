//! Atomic output: bytes for one or more paths -> files that appear complete
//! or not at all. Each file is written to a temporary file in its target
//! directory and renamed over the target only after every file of the set
//! was written, so a failed run never leaves a half-written model (nor
//! clobbers the model a previous run wrote). A path that is not a
//! regular file (`/dev/null`, `/dev/stdout`, a named pipe) is written
//! straight through instead: renaming a file over it would replace the
//! device or pipe with that file. A symbolic link is followed: its target
//! is written (atomically when it is a regular file) and the link kept.
//!
//! Every temporary file being written is listed in a registry, so that
//! the command line's signal handler removes them ([`remove_temporaries`])
//! before it exits: an interrupted run leaves no hidden `.lsys-XXXXXX`
//! beside the output. Temporary names are random and created exclusively,
//! so a stale one from a crash is never reused nor taken for output.

use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use tempfile::NamedTempFile;

use super::write_behind::WriteBehind;

/// A set of files being written; nothing is visible until [`commit`].
///
/// [`commit`]: AtomicFiles::commit
#[derive(Default)]
pub struct AtomicFiles {
    /// Target, temporary file, and its entry in the registry (dropped
    /// after the file: the file is deleted first).
    pending: Vec<(PathBuf, NamedTempFile, InFlight)>,
}

/// The temporary files being written now, for [`remove_temporaries`].
static IN_FLIGHT: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// A temporary file's entry in [`IN_FLIGHT`], removed when dropped.
struct InFlight(PathBuf);

impl InFlight {
    fn new(path: &Path) -> InFlight {
        in_flight().push(path.to_path_buf());
        InFlight(path.to_path_buf())
    }
}

impl Drop for InFlight {
    fn drop(&mut self) {
        let mut list = in_flight();
        if let Some(i) = list.iter().position(|p| *p == self.0) {
            list.swap_remove(i);
        }
    }
}

/// The registry, even if a thread panicked holding it (a list of paths
/// cannot be left half-changed).
fn in_flight() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    IN_FLIGHT.lock().unwrap_or_else(|e| e.into_inner())
}

/// Deletes every temporary file being written: for a signal handler that
/// is about to end the process (SIGINT, SIGTERM, SIGHUP), which would
/// otherwise leave them behind. Returns how many were removed.
pub fn remove_temporaries() -> usize {
    let list = in_flight();
    list.iter()
        .filter(|p| std::fs::remove_file(p).is_ok())
        .count()
}

/// An output that is also an input of the same run.
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
#[error("the output {output} is an input of this run{same}")]
#[diagnostic(
    code(lsys::export::output_is_input),
    help("writing it would replace the input with the output; name another output file (nothing was written)")
)]
pub struct OutputIsInput {
    pub output: String,
    /// `" (the same file as INPUT)"` when the input was named otherwise.
    pub same: String,
}

/// Refuses to write `output` when it is one of `inputs` (the files this
/// run read): `lsys derive plant.lsys -o plant.lsys` would replace the
/// grammar with its own output. Paths are compared canonicalised (links
/// followed); an output that does not exist yet is compared by its
/// folder's canonical path.
pub fn refuse_inputs(output: &Path, inputs: &[PathBuf]) -> Result<(), OutputIsInput> {
    let Some(out) = canonical_output(output) else {
        return Ok(());
    };
    match inputs
        .iter()
        .find(|i| std::fs::canonicalize(i).is_ok_and(|i| i == out))
    {
        Some(input) => Err(OutputIsInput {
            output: output.display().to_string(),
            same: if input == output {
                String::new()
            } else {
                format!(" (the same file as {})", input.display())
            },
        }),
        None => Ok(()),
    }
}

/// `output`'s canonical path, or that of its folder joined with its name
/// when it does not exist yet (a dangling link: its target's).
fn canonical_output(output: &Path) -> Option<PathBuf> {
    let (dest, _) = destination(output);
    if let Ok(p) = std::fs::canonicalize(&dest) {
        return Some(p);
    }
    let dir = dest
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    Some(std::fs::canonicalize(dir).ok()?.join(dest.file_name()?))
}

/// Where writing `path` goes, and whether it is written through (not a
/// regular file: a device, a pipe, a socket). A symbolic link is followed
/// to its target, so that the target is written and the link kept.
fn destination(path: &Path) -> (PathBuf, bool) {
    match std::fs::metadata(path) {
        // Opening follows the links itself (`/dev/stdout` names
        // `/proc/self/fd/1`, which may be a pipe that has no path).
        Ok(m) if !m.is_file() && !m.is_dir() => (path.to_path_buf(), true),
        Ok(_) => (
            std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf()),
            false,
        ),
        // Missing, or a link to a file not there yet: its target.
        Err(_) => {
            let mut at = path.to_path_buf();
            for _ in 0..40 {
                match std::fs::read_link(&at) {
                    Ok(t) => {
                        at = match at.parent() {
                            Some(d) if t.is_relative() => d.join(t),
                            _ => t,
                        }
                    }
                    Err(_) => break,
                }
            }
            (at, false)
        }
    }
}

/// Opens a device or named pipe for writing without waiting forever: a
/// pipe with no reader is an error (ENXIO) at once, not a hang; once
/// open, writes block as usual.
fn open_through(path: &Path) -> io::Result<std::fs::File> {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        use std::os::fd::AsRawFd;
        use std::os::unix::fs::OpenOptionsExt;
        let file = std::fs::OpenOptions::new()
            .write(true)
            .custom_flags(libc::O_NONBLOCK)
            .open(path)
            .map_err(|e| {
                if e.raw_os_error() == Some(libc::ENXIO) {
                    io::Error::new(
                        e.kind(),
                        format!(
                            "nothing is reading the named pipe {}: start its reader first, or write to a regular file",
                            path.display()
                        ),
                    )
                } else {
                    e
                }
            })?;
        let fd = file.as_raw_fd();
        // SAFETY: F_GETFL/F_SETFL on a descriptor this function owns; only
        // the O_NONBLOCK flag changes.
        unsafe {
            let flags = libc::fcntl(fd, libc::F_GETFL);
            if flags >= 0 {
                libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK);
            }
        }
        Ok(file)
    }
    #[cfg(not(all(target_os = "linux", target_env = "gnu")))]
    std::fs::OpenOptions::new().write(true).open(path)
}

impl AtomicFiles {
    pub fn new() -> Self {
        Self::default()
    }

    /// Writes one file's content with `body`. The file appears at `path` on
    /// [`commit`](AtomicFiles::commit).
    pub fn write<E: From<io::Error>>(
        &mut self,
        path: &Path,
        body: impl FnOnce(&mut dyn Write) -> Result<(), E>,
    ) -> Result<(), E> {
        let (dest, through) = destination(path);
        let path = dest.as_path();
        if through {
            let file = open_through(path)?;
            let mut out = BufWriter::with_capacity(1 << 16, file);
            body(&mut out)?;
            out.flush()?;
            return Ok(());
        }
        let dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let tmp = temporary_in(dir)?;
        let entry = InFlight::new(tmp.path());
        #[cfg(unix)]
        let fd = Some(std::os::fd::AsRawFd::as_raw_fd(&tmp));
        #[cfg(not(unix))]
        let fd = None;
        let mut out = BufWriter::with_capacity(1 << 16, WriteBehind::new(tmp, fd));
        body(&mut out)?;
        let tmp = out.into_inner().map_err(|e| e.into_error())?.finish();
        let tmp = tmp.ok_or_else(|| io::Error::other("the temporary file was already finished"))?;
        self.pending.push((path.to_path_buf(), tmp, entry));
        Ok(())
    }

    /// Renames every written file into place, in the order written (write a
    /// file that others refer to, like an `.mtl`, first). Dropping the set
    /// instead deletes the temporary files.
    pub fn commit(self) -> io::Result<()> {
        for (path, tmp, _entry) in self.pending {
            tmp.persist(&path).map_err(|e| e.error)?;
        }
        Ok(())
    }
}

/// A temporary file in `dir` with the permissions a new file would get
/// (0o666 less the umask), not tempfile's private 0o600: the temporary
/// file becomes the user's output.
fn temporary_in(dir: &Path) -> io::Result<NamedTempFile> {
    let mut b = tempfile::Builder::new();
    b.prefix(".lsys-");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        b.permissions(std::fs::Permissions::from_mode(0o666));
    }
    // tempfile's error names the temporary file ("at path
    // dir/.lsys-XXXX"), which the user never asked for: say what is wrong
    // with the folder instead (callers name the output path).
    b.tempfile_in(dir).map_err(|e| {
        let why = match e.kind() {
            io::ErrorKind::NotFound => format!("the folder {} does not exist", dir.display()),
            io::ErrorKind::PermissionDenied => {
                format!("no permission to create files in {}", dir.display())
            }
            kind => format!(
                "cannot create a file in {}: {}",
                dir.display(),
                io::Error::from(kind)
            ),
        };
        io::Error::new(e.kind(), why)
    })
}

/// Writes one file atomically.
pub fn write_file<E: From<io::Error>>(
    path: &Path,
    body: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E> {
    let mut files = AtomicFiles::new();
    files.write(path, body)?;
    files.commit().map_err(E::from)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `-o /dev/null` (or a pipe) is written through, never replaced by a
    /// regular file renamed over it. Tried on a named pipe of our own, not
    /// on the machine's /dev/null.
    #[cfg(unix)]
    #[test]
    fn devices_and_pipes_are_written_through_not_replaced() {
        use std::os::unix::fs::FileTypeExt;
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("pipe.glb");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|s| s.success()) {
            eprintln!("skipped: no mkfifo");
            return;
        }
        // Without a reader, an error at once rather than a wait forever.
        #[cfg(all(target_os = "linux", target_env = "gnu"))]
        let e = write_file::<io::Error>(&fifo, |w| w.write_all(b"glTF")).unwrap_err();
        #[cfg(all(target_os = "linux", target_env = "gnu"))]
        assert!(e.to_string().contains("nothing is reading"), "{e}");
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || std::fs::read(fifo).unwrap())
        };
        // Until the reader has the pipe open.
        let mut tries = 0;
        while let Err(e) = write_file::<io::Error>(&fifo, |w| w.write_all(b"glTF")) {
            tries += 1;
            assert!(tries < 1000, "{e}");
            std::thread::sleep(std::time::Duration::from_millis(10));
        }
        // Checked before joining: a replaced pipe would never get a writer.
        let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
        assert!(kind.is_fifo(), "the pipe was replaced by {kind:?}");
        assert_eq!(reader.join().unwrap(), b"glTF");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn failed_write_keeps_the_old_file_and_leaves_no_temporaries() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("model.obj");
        std::fs::write(&path, "old").unwrap();
        let r: io::Result<()> = write_file(&path, |w| {
            w.write_all(b"half")?;
            Err(io::Error::other("boom"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        write_file::<io::Error>(&path, |w| w.write_all(b"new")).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            // readable by others, as any new file (umask 022 or 002)
            let mode = std::fs::metadata(&path).unwrap().permissions().mode();
            assert_eq!(mode & 0o044, 0o044, "mode {mode:o}");
        }
    }
}
