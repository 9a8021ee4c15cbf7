//! The GLB's binary buffer as a plan: each piece (a mesh's positions,
//! normals or indices, or bytes already encoded) with its offset, laid out
//! as the document is built, and encoded only while it is written. Input:
//! the pieces; output: the buffer's bytes, streamed to a writer in one
//! pass, so the file is never held in memory as a whole.

use std::io::{self, Write};
use std::sync::mpsc::{channel, sync_channel, Receiver, SyncSender};

use glam::{Mat3, Mat4, Vec3};

use super::super::padded;
use super::unit_normals;
use crate::mesh::TriMesh;

/// One run of bytes in the buffer.
pub(super) enum Piece<'s> {
    /// `mesh`'s vertex positions mapped by the transform, f32 x 3 each.
    Positions(&'s TriMesh, Mat4),
    /// `mesh`'s unit normals under the linear map, f32 x 3 each; `true`
    /// when some normal collapses and must be repaired from the faces
    /// (see [`unit_normals`]), else each is mapped as it is written.
    Normals(&'s TriMesh, Mat3, bool),
    /// `mesh`'s indices, two corners swapped when `flip`, as u16 when
    /// `small`, else u32.
    Indices {
        mesh: &'s TriMesh,
        flip: bool,
        small: bool,
    },
    Bytes(Vec<u8>),
    /// Bytes the scene holds (a texture's image), written as they are.
    Slice(&'s [u8]),
}

impl Piece<'_> {
    fn len(&self) -> usize {
        match self {
            Piece::Positions(m, _) | Piece::Normals(m, _, _) => m.positions.len() * 12,
            Piece::Indices { mesh, small, .. } => mesh.indices.len() * if *small { 2 } else { 4 },
            Piece::Bytes(b) => b.len(),
            Piece::Slice(b) => b.len(),
        }
    }
}

#[derive(Default)]
pub(crate) struct Bin<'s> {
    pieces: Vec<(usize, Piece<'s>)>,
    len: usize,
}

impl<'s> Bin<'s> {
    /// The next offset, 4-byte aligned (every accessor's components must be
    /// aligned to their size).
    pub fn align(&mut self) -> usize {
        self.len = padded(self.len);
        self.len
    }

    /// Adds `piece` at the (aligned) end; returns its offset.
    pub(super) fn push(&mut self, piece: Piece<'s>) -> usize {
        let start = self.align();
        self.len += piece.len();
        self.pieces.push((start, piece));
        start
    }

    /// The end of the last piece (unpadded).
    pub fn end(&self) -> usize {
        self.len
    }

    /// The buffer's length, padded to 4 bytes.
    pub fn len(&self) -> usize {
        padded(self.len)
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Writes the buffer (zero padding included) to `out`. A big buffer is
    /// encoded on a second thread while this one writes what is ready.
    pub fn write_to(&self, out: &mut dyn Write) -> io::Result<()> {
        if self.len() >= PIPELINE_FROM && crate::derive::threads() >= 2 {
            return self.write_pipelined(out);
        }
        let mut blocks = Blocks {
            sink: Sink::Out(out),
            block: Vec::with_capacity(2 * BLOCK),
            size: BLOCK,
        };
        self.encode_all(&mut blocks)
    }

    /// Encodes on a helper thread in blocks of [`PIPELINE_BLOCK`], written
    /// here as they come: the encoding and the kernel's copy into the page
    /// cache (each about half of writing W2's 54 MB) overlap. The same
    /// bytes in the same order as [`Bin::write_to`] on one thread.
    fn write_pipelined(&self, out: &mut dyn Write) -> io::Result<()> {
        let (full, full_rx) = sync_channel::<Vec<u8>>(IN_FLIGHT);
        let (empty_tx, empty) = channel::<Vec<u8>>();
        std::thread::scope(|scope| {
            let encoder = scope.spawn(move || {
                let mut blocks = Blocks {
                    sink: Sink::Channel { full, empty },
                    block: Vec::with_capacity(2 * PIPELINE_BLOCK),
                    size: PIPELINE_BLOCK,
                };
                self.encode_all(&mut blocks)
            });
            let mut written = Ok(());
            for mut block in full_rx.iter() {
                if let Err(e) = out.write_all(&block) {
                    written = Err(e);
                    break;
                }
                block.clear();
                let _ = empty_tx.send(block);
            }
            // A failed write ends the encoder at its next block.
            drop(full_rx);
            let encoded = encoder
                .join()
                .unwrap_or_else(|_| Err(io::Error::other("encoding the GLB buffer failed")));
            // The writer's error first: the encoder's is only that the
            // writer stopped.
            written.and(encoded)
        })
    }

    fn encode_all(&self, blocks: &mut Blocks) -> io::Result<()> {
        let mut at = 0;
        let mut scratch = Vec::new();
        for (start, piece) in &self.pieces {
            blocks.zeros(start - at);
            at = start + piece.len();
            match piece {
                Piece::Positions(mesh, transform) if is_identity(transform) => {
                    // The identity maps each coordinate to itself plus the
                    // translation's +0.0 (the terms of the other
                    // coordinates are ±0): -0.0 becomes +0.0, all else is
                    // kept. The positions are finite (`Builder::geometry`
                    // checked them), where `c + 0.0` is exactly that.
                    blocks.encode(&mesh.positions, 12, 1, |ps, dst| {
                        for (&p, d) in ps.iter().zip(dst.chunks_exact_mut(12)) {
                            put_vec3(d, p + Vec3::ZERO);
                        }
                    })?;
                }
                Piece::Positions(mesh, transform) => {
                    blocks.encode(&mesh.positions, 12, 1, |ps, dst| {
                        for (&p, d) in ps.iter().zip(dst.chunks_exact_mut(12)) {
                            put_vec3(d, transform.transform_point3(p));
                        }
                    })?;
                }
                Piece::Normals(mesh, linear, true) => {
                    unit_normals(mesh, *linear, &mut scratch);
                    blocks.encode(&scratch, 12, 1, |ns, dst| {
                        for (&n, d) in ns.iter().zip(dst.chunks_exact_mut(12)) {
                            put_vec3(d, n);
                        }
                    })?;
                }
                Piece::Normals(mesh, linear, false) => {
                    let normal_matrix = linear.inverse().transpose();
                    blocks.encode(&mesh.normals, 12, 1, |ns, dst| {
                        for (&n, d) in ns.iter().zip(dst.chunks_exact_mut(12)) {
                            put_vec3(d, (normal_matrix * n).normalize_or_zero());
                        }
                    })?;
                }
                Piece::Indices { mesh, flip, small } => {
                    // Each size spelt out: a size known only at run time
                    // made every index a call to memcpy.
                    let triangles = |t: &[u32]| {
                        let (a, b, c) = (t[0], t[1], t[2]);
                        if *flip {
                            [a, c, b]
                        } else {
                            [a, b, c]
                        }
                    };
                    if *small {
                        blocks.encode(&mesh.indices, 2, 3, |is, dst| {
                            for (t, d) in is.chunks_exact(3).zip(dst.chunks_exact_mut(6)) {
                                for (i, d) in triangles(t).into_iter().zip(d.chunks_exact_mut(2)) {
                                    d.copy_from_slice(&(i as u16).to_le_bytes());
                                }
                            }
                        })?;
                    } else if *flip {
                        blocks.encode(&mesh.indices, 4, 3, |is, dst| {
                            for (t, d) in is.chunks_exact(3).zip(dst.chunks_exact_mut(12)) {
                                for (i, d) in triangles(t).into_iter().zip(d.chunks_exact_mut(4)) {
                                    d.copy_from_slice(&i.to_le_bytes());
                                }
                            }
                        })?;
                    } else {
                        blocks.encode(&mesh.indices, 4, 1, |is, dst| {
                            for (&i, d) in is.iter().zip(dst.chunks_exact_mut(4)) {
                                d.copy_from_slice(&i.to_le_bytes());
                            }
                        })?;
                    }
                }
                Piece::Bytes(bytes) => blocks.bytes(bytes)?,
                Piece::Slice(bytes) => blocks.bytes(bytes)?,
            }
        }
        blocks.zeros(self.len() - at);
        blocks.flush()
    }

    /// The buffer's bytes in memory (for a `.gltf` data URI).
    pub fn to_vec(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.len());
        // Writing to a Vec cannot fail.
        let _ = self.write_to(&mut out);
        out
    }
}

/// Bytes encoded before each write: a few writes per mesh, no copy of it.
const BLOCK: usize = 1 << 16;

/// A buffer this big is encoded on a second thread.
const PIPELINE_FROM: usize = 8 << 20;

/// Bytes a block the encoder thread hands over.
const PIPELINE_BLOCK: usize = 512 << 10;

/// Blocks encoded ahead of the writer, at most.
const IN_FLIGHT: usize = 2;

/// Where full blocks go.
enum Sink<'w> {
    /// Written here and now.
    Out(&'w mut dyn Write),
    /// Handed to the writing thread, which sends emptied blocks back.
    Channel {
        full: SyncSender<Vec<u8>>,
        empty: Receiver<Vec<u8>>,
    },
}

/// The buffer being written: bytes are encoded into `block`, which goes
/// out whenever it holds `size` bytes or more.
struct Blocks<'w> {
    sink: Sink<'w>,
    block: Vec<u8>,
    size: usize,
}

impl Blocks<'_> {
    fn zeros(&mut self, n: usize) {
        self.block.resize(self.block.len() + n, 0);
    }

    fn flush(&mut self) -> io::Result<()> {
        match &mut self.sink {
            Sink::Out(out) => {
                out.write_all(&self.block)?;
                self.block.clear();
            }
            Sink::Channel { full, empty } => {
                if self.block.is_empty() {
                    return Ok(());
                }
                // A block the writer is done with, or (while the first
                // ones are in flight) a new one.
                let next = empty
                    .try_recv()
                    .unwrap_or_else(|_| Vec::with_capacity(self.block.capacity()));
                let block = std::mem::replace(&mut self.block, next);
                full.send(block)
                    .map_err(|_| io::Error::other("the GLB writer stopped"))?;
            }
        }
        Ok(())
    }

    /// Bytes already encoded: written as they are where that saves a copy.
    fn bytes(&mut self, bytes: &[u8]) -> io::Result<()> {
        if let Sink::Out(_) = self.sink {
            self.flush()?;
            if let Sink::Out(out) = &mut self.sink {
                out.write_all(bytes)?;
            }
            return Ok(());
        }
        self.block.extend_from_slice(bytes);
        if self.block.len() >= self.size {
            self.flush()?;
        }
        Ok(())
    }

    /// Encodes `items`, `size` bytes each, a run of whole groups of
    /// `group` at a time: `put(run, bytes)` fills the run's bytes. A run
    /// is a block's worth, so that `put`'s loop has no per-item bounds or
    /// capacity checks (an item at a time, they were most of the cost).
    fn encode<T>(
        &mut self,
        items: &[T],
        size: usize,
        group: usize,
        put: impl Fn(&[T], &mut [u8]),
    ) -> io::Result<()> {
        let per_run = (self.size / size / group).max(1) * group;
        for run in items.chunks(per_run) {
            let from = self.block.len();
            self.block.resize(from + run.len() * size, 0);
            put(run, &mut self.block[from..]);
            if self.block.len() >= self.size {
                self.flush()?;
            }
        }
        Ok(())
    }
}

/// True when `m` is the identity bit for bit (a -0.0 entry changes the
/// sign of zero coordinates).
pub(super) fn is_identity(m: &Mat4) -> bool {
    m.to_cols_array().map(f32::to_bits) == Mat4::IDENTITY.to_cols_array().map(f32::to_bits)
}

fn put_vec3(out: &mut [u8], v: Vec3) {
    for (d, c) in out.chunks_exact_mut(4).zip(v.to_array()) {
        d.copy_from_slice(&c.to_le_bytes());
    }
}

/// `v`'s little-endian f32 bytes, for [`Piece::Bytes`].
pub(super) fn f32_bytes(out: &mut Vec<u8>, values: impl IntoIterator<Item = f32>) {
    for c in values {
        out.extend_from_slice(&c.to_le_bytes());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pieces start 4-byte aligned with zero padding between them, and the
    /// streamed bytes (through a writer that takes a few bytes at a time)
    /// are the laid-out length.
    #[test]
    fn pieces_are_aligned_padded_and_streamed_whole() {
        let mut mesh = TriMesh::cuboid(Vec3::ZERO, Vec3::ONE);
        mesh.indices.truncate(3); // 3 u16 indices: 6 bytes, then padding
        let mut bin = Bin::default();
        let a = bin.push(Piece::Indices {
            mesh: &mesh,
            flip: true,
            small: true,
        });
        let b = bin.push(Piece::Bytes(vec![7; 5]));
        let c = bin.push(Piece::Positions(&mesh, Mat4::from_translation(Vec3::X)));
        assert_eq!((a, b, c), (0, 8, 16));
        assert_eq!(bin.len(), 16 + 24 * 12);
        struct Trickle(Vec<u8>);
        impl Write for Trickle {
            fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
                let n = buf.len().min(3);
                self.0.extend_from_slice(&buf[..n]);
                Ok(n)
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let mut out = Trickle(Vec::new());
        bin.write_to(&mut out).unwrap();
        let bytes = out.0;
        assert_eq!(bytes, bin.to_vec());
        assert_eq!(bytes.len(), bin.len());
        let t = &mesh.indices;
        let u16s: Vec<u16> = bytes[..6]
            .chunks(2)
            .map(|c| u16::from_le_bytes([c[0], c[1]]))
            .collect();
        assert_eq!(u16s, [t[0] as u16, t[2] as u16, t[1] as u16]);
        assert_eq!(&bytes[6..8], &[0, 0]);
        assert_eq!(&bytes[8..13], &[7; 5]);
        assert_eq!(&bytes[13..16], &[0, 0, 0]);
        let x = f32::from_le_bytes(bytes[16..20].try_into().unwrap());
        assert_eq!(x, mesh.positions[0].x + 1.0);
    }

    /// A buffer big enough for two threads gives the bytes of one thread,
    /// and a writer that fails stops the encoder with the writer's error.
    #[test]
    fn the_pipelined_buffer_is_the_one_thread_buffer() {
        let mut mesh = TriMesh::default();
        let n = 400_000; // 4.8 MB of positions, as much of normals, 4.8 of indices
        mesh.positions = (0..n).map(|i| Vec3::new(i as f32, -0.0, 0.5)).collect();
        mesh.normals = vec![Vec3::Z; n];
        mesh.indices = (0..3 * n as u32).map(|i| i % n as u32).collect();
        let mut bin = Bin::default();
        bin.push(Piece::Positions(&mesh, Mat4::IDENTITY));
        bin.push(Piece::Bytes(vec![9; 3]));
        bin.push(Piece::Normals(&mesh, Mat3::IDENTITY, false));
        bin.push(Piece::Indices {
            mesh: &mesh,
            flip: true,
            small: false,
        });
        assert!(bin.len() >= PIPELINE_FROM);
        let mut one = Vec::new();
        bin.encode_all(&mut Blocks {
            sink: Sink::Out(&mut one),
            block: Vec::new(),
            size: BLOCK,
        })
        .unwrap();
        let mut two = Vec::new();
        bin.write_pipelined(&mut two).unwrap();
        assert_eq!(one.len(), bin.len());
        assert!(one == two, "the pipelined bytes differ");

        struct FailsAfter(usize);
        impl Write for FailsAfter {
            fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
                if self.0 < buf.len() {
                    return Err(io::Error::new(io::ErrorKind::StorageFull, "full"));
                }
                self.0 -= buf.len();
                Ok(buf.len())
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let e = bin.write_pipelined(&mut FailsAfter(3 << 20)).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::StorageFull);
    }
}
