//! The GLB's binary buffer as a plan: each piece (a mesh's positions,
//! normals or indices, or bytes already encoded) with its offset, laid out
//! as the document is built, and encoded only while it is written. Input:
//! the pieces; output: the buffer's bytes, streamed to a writer in one
//! pass, so the file is never held in memory as a whole.

use std::io::{self, Write};

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
}

impl Piece<'_> {
    fn len(&self) -> usize {
        match self {
            Piece::Positions(m, _) | Piece::Normals(m, _, _) => m.positions.len() * 12,
            Piece::Indices { mesh, small, .. } => mesh.indices.len() * if *small { 2 } else { 4 },
            Piece::Bytes(b) => b.len(),
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

    /// Writes the buffer (zero padding included) to `out`.
    pub fn write_to(&self, out: &mut dyn Write) -> io::Result<()> {
        // Encoded a block at a time: a few writes per mesh, no copy of it.
        const BLOCK: usize = 1 << 16;
        let mut block: Vec<u8> = Vec::with_capacity(BLOCK + 16);
        let mut at = 0;
        let mut scratch = Vec::new();
        for (start, piece) in &self.pieces {
            block.resize(block.len() + (start - at), 0);
            at = start + piece.len();
            let mut flush = |block: &mut Vec<u8>| -> io::Result<()> {
                if block.len() >= BLOCK {
                    out.write_all(block)?;
                    block.clear();
                }
                Ok(())
            };
            match piece {
                Piece::Positions(mesh, transform) => {
                    for &p in &mesh.positions {
                        put_vec3(&mut block, transform.transform_point3(p));
                        flush(&mut block)?;
                    }
                }
                Piece::Normals(mesh, linear, true) => {
                    unit_normals(mesh, *linear, &mut scratch);
                    for &n in &scratch {
                        put_vec3(&mut block, n);
                        flush(&mut block)?;
                    }
                }
                Piece::Normals(mesh, linear, false) => {
                    let normal_matrix = linear.inverse().transpose();
                    for &n in &mesh.normals {
                        put_vec3(&mut block, (normal_matrix * n).normalize_or_zero());
                        flush(&mut block)?;
                    }
                }
                Piece::Indices { mesh, flip, small } => {
                    for t in mesh.indices.chunks_exact(3) {
                        let t = if *flip {
                            [t[0], t[2], t[1]]
                        } else {
                            [t[0], t[1], t[2]]
                        };
                        for i in t {
                            if *small {
                                block.extend_from_slice(&(i as u16).to_le_bytes());
                            } else {
                                block.extend_from_slice(&i.to_le_bytes());
                            }
                        }
                        flush(&mut block)?;
                    }
                }
                Piece::Bytes(bytes) => {
                    out.write_all(&block)?;
                    block.clear();
                    out.write_all(bytes)?;
                }
            }
        }
        block.resize(block.len() + (self.len() - at), 0);
        out.write_all(&block)
    }

    /// The buffer's bytes in memory (for a `.gltf` data URI).
    pub fn to_vec(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.len());
        // Writing to a Vec cannot fail.
        let _ = self.write_to(&mut out);
        out
    }
}

fn put_vec3(out: &mut Vec<u8>, v: Vec3) {
    for c in v.to_array() {
        out.extend_from_slice(&c.to_le_bytes());
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
}
