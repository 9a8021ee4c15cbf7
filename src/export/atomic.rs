//! Atomic output: bytes for one or more paths -> files that appear complete
//! or not at all. Each file is written to a temporary file in its target
//! directory and renamed over the target only after every file of the set
//! was written, so a failed run never leaves a half-written model (nor
//! clobbers the model a previous run wrote). A path that is not a
//! regular file (`/dev/null`, `/dev/stdout`, a named pipe) is written
//! straight through instead: renaming a file over it would replace the
//! device or pipe with that file.

use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;

use super::write_behind::WriteBehind;

/// A set of files being written; nothing is visible until [`commit`].
///
/// [`commit`]: AtomicFiles::commit
#[derive(Default)]
pub struct AtomicFiles {
    pending: Vec<(PathBuf, NamedTempFile)>,
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
        if is_special(path) {
            let file = std::fs::OpenOptions::new().write(true).open(path)?;
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
        #[cfg(unix)]
        let fd = Some(std::os::fd::AsRawFd::as_raw_fd(&tmp));
        #[cfg(not(unix))]
        let fd = None;
        let mut out = BufWriter::with_capacity(1 << 16, WriteBehind::new(tmp, fd));
        body(&mut out)?;
        let tmp = out.into_inner().map_err(|e| e.into_error())?.finish();
        let tmp = tmp.ok_or_else(|| io::Error::other("the temporary file was already finished"))?;
        self.pending.push((path.to_path_buf(), tmp));
        Ok(())
    }

    /// Renames every written file into place, in the order written (write a
    /// file that others refer to, like an `.mtl`, first). Dropping the set
    /// instead deletes the temporary files.
    pub fn commit(self) -> io::Result<()> {
        for (path, tmp) in self.pending {
            tmp.persist(&path).map_err(|e| e.error)?;
        }
        Ok(())
    }
}

/// Whether `path` exists and is neither a regular file nor a folder: a
/// device, a named pipe or a socket (symbolic links followed).
fn is_special(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
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
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || std::fs::read(fifo).unwrap())
        };
        write_file::<io::Error>(&fifo, |w| w.write_all(b"glTF")).unwrap();
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
