//! Write-behind for big output files: bytes for a temporary file -> the
//! same bytes in it, with the kernel told, on a helper thread, to start
//! writing each [`STEP`] back to disk as soon as it is written.
//!
//! Why: [`super::atomic`] renames the finished file over the old one, and
//! ext4 (its `auto_da_alloc` safeguard, which keeps a crash from leaving an
//! empty file) then starts writing the whole new file back inside the
//! rename, with the second core idle: with freeing the old file, 21 ms
//! of W2's 0.2 s build. Started while the file is still being written,
//! that writeback is under way by the rename. `sync_file_range(WRITE)`
//! only starts writeback: it neither waits for the disk nor changes the
//! file, and what it cannot do is left to the rename as before. (Freeing
//! the old file's blocks stays in the rename: see
//! docs/performance/issue-19-rounds-5-7.md, round 7.)

use std::io::{self, Write};
use std::sync::mpsc::{channel, Sender};
use std::thread::JoinHandle;

/// Bytes written between two requests to start writeback.
const STEP: u64 = 8 << 20;

/// A file being written, its written bytes sent back to disk a
/// [`STEP`] at a time.
pub(super) struct WriteBehind<F> {
    /// `Some` until `finish` takes it.
    file: Option<F>,
    /// The file's descriptor, for the helper (`None`: no write-behind).
    fd: Option<i32>,
    written: u64,
    /// Where the next request starts.
    asked: u64,
    helper: Option<Helper>,
    /// The ranges asked for, for the tests.
    #[cfg(test)]
    asked_for: Vec<(u64, u64)>,
}

/// The helper thread and the channel that sends it ranges.
struct Helper {
    to: Sender<(u64, u64)>,
    thread: JoinHandle<()>,
}

impl<F> WriteBehind<F> {
    /// `fd` is `file`'s descriptor; it must stay open as long as `file`.
    pub(super) fn new(file: F, fd: Option<i32>) -> Self {
        WriteBehind {
            file: Some(file),
            fd,
            written: 0,
            asked: 0,
            helper: None,
            #[cfg(test)]
            asked_for: Vec::new(),
        }
    }

    /// Asks for the bytes written since the last request to be written
    /// back, starting the helper the first time.
    fn ask(&mut self) {
        let range = (self.asked, self.written - self.asked);
        self.asked = self.written;
        if self.helper.is_none() {
            self.helper = self.fd.and_then(start);
            // Once: a file whose helper could not start goes on without.
            self.fd = None;
        }
        if let Some(h) = &self.helper {
            let _ = h.to.send(range);
            #[cfg(test)]
            self.asked_for.push(range);
        }
    }

    /// The file, once the helper has made its last request. A file smaller
    /// than [`STEP`] never started one.
    pub(super) fn finish(mut self) -> Option<F> {
        if self.helper.is_some() && self.written > self.asked {
            self.ask();
        }
        self.join();
        self.file.take()
    }

    fn join(&mut self) {
        if let Some(Helper { to, thread }) = self.helper.take() {
            drop(to);
            let _ = thread.join();
        }
    }
}

/// A write that failed drops the file unfinished: the helper must be done
/// with its descriptor before the file is closed (and the number reused).
impl<F> Drop for WriteBehind<F> {
    fn drop(&mut self) {
        self.join();
    }
}

impl<F: Write> Write for WriteBehind<F> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let Some(file) = self.file.as_mut() else {
            return Err(io::Error::other("write-behind: file already finished"));
        };
        let n = file.write(buf)?;
        self.written += n as u64;
        if self.written - self.asked >= STEP {
            self.ask();
        }
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.file.as_mut().map_or(Ok(()), |f| f.flush())
    }
}

/// The helper: `sync_file_range(WRITE)` for each range it is sent, until
/// the sender is dropped. The file outlives it: `finish` joins it before
/// giving the file back.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn start(fd: i32) -> Option<Helper> {
    if crate::derive::threads() < 2 {
        return None;
    }
    let (to, from) = channel::<(u64, u64)>();
    let thread = std::thread::Builder::new()
        .name("lsys-write-behind".into())
        .spawn(move || {
            for (offset, len) in from {
                // SAFETY: `fd` stays open until this thread is joined; the
                // call only starts writeback of pages already written.
                unsafe {
                    libc::sync_file_range(
                        fd,
                        offset as libc::off64_t,
                        len as libc::off64_t,
                        libc::SYNC_FILE_RANGE_WRITE,
                    );
                }
            }
        })
        .ok()?;
    Some(Helper { to, thread })
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn start(_fd: i32) -> Option<Helper> {
    None
}

#[cfg(all(test, target_os = "linux", target_env = "gnu"))]
mod tests {
    use super::*;
    use std::os::fd::AsRawFd;

    /// A file of 2.5 steps is asked back a step at a time and its rest at
    /// the end, with no gap or overlap, and its bytes are the ones written.
    #[test]
    fn every_byte_is_asked_back_once_and_written_as_given() {
        if crate::derive::threads() < 2 {
            eprintln!("skipped: one thread, no write-behind");
            return;
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("big");
        let file = std::fs::File::create(&path).unwrap();
        let fd = file.as_raw_fd();
        let mut w = WriteBehind::new(file, Some(fd));
        let block: Vec<u8> = (0..=255u8).cycle().take(1 << 20).collect();
        for _ in 0..(5 * STEP / 2) >> 20 {
            w.write_all(&block).unwrap();
        }
        // What `finish` does first: ask for the rest.
        w.ask();
        assert_eq!(w.asked_for, [(0, STEP), (STEP, STEP), (2 * STEP, STEP / 2)]);
        drop(w.finish().unwrap());
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(bytes.len() as u64, 5 * STEP / 2);
        assert!(bytes.chunks(1 << 20).all(|c| c == block.as_slice()));
    }

    /// A small file never starts the helper; no descriptor, no helper.
    #[test]
    fn small_files_and_no_descriptor_start_no_helper() {
        let mut w = WriteBehind::new(Vec::new(), None);
        w.write_all(&vec![1; (STEP + 1) as usize]).unwrap();
        assert!(w.helper.is_none());
        let dir = tempfile::tempdir().unwrap();
        let file = std::fs::File::create(dir.path().join("small")).unwrap();
        let fd = file.as_raw_fd();
        let mut w = WriteBehind::new(file, Some(fd));
        w.write_all(b"glTF").unwrap();
        assert!(w.helper.is_none());
        assert!(w.finish().is_some());
    }
}
