//! The fresh pages of big buffers (`Vec`s reserved up front and filled from
//! the front), backed on the second core while the first fills them. Input:
//! the buffers' addresses, capacities and lengths as their writer goes;
//! output: nothing but pages the kernel has already backed when the writer
//! gets to them. The turtle uses it for a big drawing's chains, the mesher
//! for a big mesh's positions, normals and indices.
//!
//! Why: on this kind of machine the first touch of a 4 KiB page costs
//! 1.7 to 4.5 µs (backing and zeroing it), and a big model is mostly fresh
//! pages: the faults in W2's 54 MB of positions, normals and indices were
//! half its tube-meshing time. `MADV_POPULATE_WRITE` does that work for a
//! range of addresses without reading or writing its bytes, so a helper
//! thread can work in the same buffers a little ahead of the writer. It
//! stays at most [`LEAD`] bytes ahead of each buffer's length, so the
//! pages it backs are ones the writer is about to fill (the capacity
//! reserved is an upper bound, several times what W2 uses).
//!
//! If a buffer outgrows its capacity it moves; the writer then stops the
//! helper. A range the helper is still working on may have been freed by
//! then: populating it changes no byte of it (it only backs pages), and a
//! range no longer mapped is an error the helper stops at.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;

/// How far ahead of the writer, in bytes, the helper backs pages.
const LEAD: usize = 1 << 20;

/// What the helper backs in one call (and how much further a buffer must
/// be before the helper is woken).
const CHUNK: usize = 128 << 10;

/// Spare capacity below this (all buffers) is not worth a thread.
const MIN_SPARE: usize = 8 << 20;

const PAGE: usize = 4096;

/// One buffer as the helper sees it: the address of its first element, its
/// capacity and its length, in bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    ptr: usize,
    cap: usize,
    len: usize,
}

/// `v` as a [`Region`].
pub fn region<T>(v: &Vec<T>) -> Region {
    let size = std::mem::size_of::<T>();
    Region {
        ptr: v.as_ptr() as usize,
        cap: v.capacity() * size,
        len: v.len() * size,
    }
}

/// One buffer's end (address) and the address up to which the writer has
/// written it.
struct Buffer {
    end: usize,
    written: AtomicUsize,
}

struct Shared<const N: usize> {
    buffers: [Buffer; N],
    stop: AtomicBool,
}

/// A helper backing the pages of `N` buffers ahead of their writer.
/// Dropping it stops and joins the helper.
pub struct Prefault<const N: usize> {
    shared: Arc<Shared<N>>,
    /// The buffers' addresses and capacities when the helper started.
    at: [(usize, usize); N],
    /// The written addresses last told to the helper.
    told: [usize; N],
    /// The writer's count at which `progress` next looks at the buffers,
    /// and how far apart the looks are.
    look_at: usize,
    look_every: usize,
    helper: Option<JoinHandle<()>>,
}

impl<const N: usize> Prefault<N> {
    /// Starts a helper over the spare capacity of `now` (buffers reserved up
    /// front) when there is enough of it and `threads` (the threads the work
    /// may use) is at least two. The writer tells of its progress by a count
    /// of its own (items written), at which the buffers are looked at every
    /// `look_every`. `None`: the writer works alone, as before.
    pub fn start(now: [Region; N], threads: usize, look_every: usize) -> Option<Prefault<N>> {
        if threads < 2 || !cfg!(all(target_os = "linux", target_env = "gnu")) {
            return None;
        }
        let spare: usize = now.iter().map(|r| r.cap - r.len).sum();
        if spare < MIN_SPARE {
            return None;
        }
        let shared = Arc::new(Shared {
            buffers: now.map(|r| Buffer {
                end: r.ptr + r.cap,
                written: AtomicUsize::new(r.ptr + r.len),
            }),
            stop: AtomicBool::new(false),
        });
        let theirs = Arc::clone(&shared);
        let helper = std::thread::Builder::new()
            .name("lsys-prefault".into())
            .spawn(move || run(&theirs))
            .ok()?;
        Some(Prefault {
            shared,
            at: now.map(|r| (r.ptr, r.cap)),
            told: now.map(|r| r.ptr + r.len),
            look_at: 0,
            look_every,
            helper: Some(helper),
        })
    }

    /// Tells the helper how far the writer has got: `count` is the writer's
    /// own measure of it; the buffers (`now()`) are looked at once every
    /// `look_every` of it, and the helper is woken once a buffer is a
    /// [`CHUNK`] further (waking it after every item was a system call
    /// each). Stops the helper when a buffer has moved.
    #[inline]
    pub fn progress(&mut self, count: usize, now: impl FnOnce() -> [Region; N]) {
        // Cheap enough to call after every item: most calls end here.
        if count < self.look_at {
            return;
        }
        self.look_at = count + self.look_every;
        self.tell(now());
    }

    #[cold]
    fn tell(&mut self, now: [Region; N]) {
        let Some(helper) = &self.helper else { return };
        if now.iter().zip(&self.at).any(|(n, a)| (n.ptr, n.cap) != *a) {
            self.finish();
            return;
        }
        let mut news = false;
        for ((b, told), r) in self.shared.buffers.iter().zip(&mut self.told).zip(now) {
            if r.ptr + r.len >= *told + CHUNK {
                *told = r.ptr + r.len;
                b.written.store(*told, Ordering::Relaxed);
                news = true;
            }
        }
        if news {
            helper.thread().unpark();
        }
    }

    /// Stops and joins the helper.
    pub fn finish(&mut self) {
        self.shared.stop.store(true, Ordering::Relaxed);
        if let Some(h) = self.helper.take() {
            h.thread().unpark();
            let _ = h.join();
        }
    }
}

impl<const N: usize> Drop for Prefault<N> {
    fn drop(&mut self) {
        self.finish();
    }
}

/// The helper: backs each buffer up to [`LEAD`] bytes past what the writer
/// has written, a [`CHUNK`] at a time, the buffer it is least ahead in
/// first; waits when it is ahead in all.
fn run<const N: usize>(shared: &Shared<N>) {
    let mut done = shared
        .buffers
        .each_ref()
        .map(|b| b.written.load(Ordering::Relaxed) & !(PAGE - 1));
    while !shared.stop.load(Ordering::Relaxed) {
        let mut next: Option<(usize, usize)> = None;
        for (i, b) in shared.buffers.iter().enumerate() {
            let written = b.written.load(Ordering::Relaxed);
            let target = (written + LEAD).min(b.end);
            done[i] = done[i].max(written & !(PAGE - 1));
            if done[i] < target {
                let ahead = done[i] - written.min(done[i]);
                if next.map_or(true, |(_, a)| ahead < a) {
                    next = Some((i, ahead));
                }
            }
        }
        let Some((i, _)) = next else {
            // Ahead everywhere: wait for the writer's next progress.
            std::thread::park_timeout(Duration::from_millis(1));
            continue;
        };
        let target =
            (shared.buffers[i].written.load(Ordering::Relaxed) + LEAD).min(shared.buffers[i].end);
        let to = (done[i] + CHUNK).min(target).next_multiple_of(PAGE);
        if !populate(done[i], to - done[i]) {
            return;
        }
        done[i] = to;
    }
}

/// Backs the pages of `len` bytes from `addr` (page aligned) for writing,
/// leaving their bytes as they are. False: the kernel refused (too old for
/// `MADV_POPULATE_WRITE`, or the range is no longer mapped).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn populate(addr: usize, len: usize) -> bool {
    // SAFETY: MADV_POPULATE_WRITE only faults pages in (as a write would)
    // without changing their contents; on a range that is not mapped it
    // fails with ENOMEM and does nothing.
    unsafe { libc::madvise(addr as *mut libc::c_void, len, libc::MADV_POPULATE_WRITE) == 0 }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn populate(_addr: usize, _len: usize) -> bool {
    false
}

#[cfg(all(test, target_os = "linux", target_env = "gnu"))]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Three buffers, as a mesh has.
    #[derive(Default)]
    struct TriMesh {
        positions: Vec<Vec3>,
        normals: Vec<Vec3>,
        indices: Vec<u32>,
    }

    fn regions(m: &TriMesh) -> [Region; 3] {
        [region(&m.positions), region(&m.normals), region(&m.indices)]
    }

    /// How many of the pages of `len` bytes from `addr` are resident.
    fn resident(addr: usize, len: usize) -> usize {
        let start = addr & !(PAGE - 1);
        let pages = (addr + len - start).div_ceil(PAGE);
        let mut vec = vec![0u8; pages];
        // SAFETY: the range lies in a live allocation; mincore only reads
        // the page tables.
        let ok = unsafe {
            libc::mincore(
                start as *mut libc::c_void,
                pages * PAGE,
                vec.as_mut_ptr().cast(),
            )
        };
        assert_eq!(ok, 0, "mincore");
        vec.iter().filter(|&&v| v & 1 != 0).count()
    }

    fn waits_for(mut f: impl FnMut() -> bool) -> bool {
        for _ in 0..400 {
            if f() {
                return true;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        false
    }

    /// The helper backs the pages just past what was written, no further
    /// than its lead, follows the writes, and leaves every byte as written.
    #[test]
    fn the_helper_backs_the_pages_ahead_of_the_writes_and_no_further() {
        let probe = vec![0u8; 2 * PAGE];
        if !populate(probe.as_ptr() as usize & !(PAGE - 1), PAGE) {
            eprintln!("skipped: this kernel has no MADV_POPULATE_WRITE");
            return;
        }
        let mut mesh = TriMesh::default();
        let n = 4 << 20; // 48 MB of positions
        mesh.positions.reserve(n);
        mesh.normals.reserve(16);
        mesh.indices.reserve(16);
        let mut p = Prefault::start(regions(&mesh), 2, 1).expect("a helper for 48 MB");
        let base = mesh.positions.as_ptr() as usize;
        let far = base + 4 * LEAD;
        assert!(waits_for(|| resident(base, LEAD) * PAGE >= LEAD - PAGE));
        assert_eq!(resident(far, LEAD), 0, "backed past its lead");
        // Write well past the first lead: the helper follows.
        let count = (3 * LEAD) / 12;
        mesh.positions
            .extend((0..count).map(|i| Vec3::splat(i as f32)));
        p.progress(usize::MAX / 2, || regions(&mesh));
        let written_end = base + count * 12;
        assert!(waits_for(
            || resident(written_end, LEAD - CHUNK) * PAGE >= LEAD - CHUNK - PAGE
        ));
        assert_eq!(resident(written_end + LEAD + CHUNK, LEAD), 0);
        p.finish();
        assert!(mesh
            .positions
            .iter()
            .enumerate()
            .all(|(i, v)| *v == Vec3::splat(i as f32)));
    }

    /// A buffer that outgrows its capacity moves: the helper stops.
    #[test]
    fn a_buffer_that_moves_stops_the_helper() {
        let mut mesh = TriMesh::default();
        mesh.indices.reserve(4 << 20);
        let mut p = Prefault::start(regions(&mesh), 2, 1).expect("a helper for 16 MB");
        mesh.indices.resize((4 << 20) + 1, 7);
        p.progress(usize::MAX / 2, || regions(&mesh));
        assert!(p.helper.is_none());
    }

    #[test]
    fn no_helper_for_one_thread_or_a_small_mesh() {
        let mut mesh = TriMesh::default();
        assert!(Prefault::start(regions(&mesh), 2, 1).is_none());
        mesh.indices.reserve(4 << 20);
        assert!(Prefault::start(regions(&mesh), 1, 1).is_none());
        assert!(Prefault::start(regions(&mesh), 2, 1).is_some());
    }
}
