//! SGI image files (`.rgb`, `.bw`, `.sgi`), the format vlab's clover
//! program reads its light field from: the file's bytes in; its channels
//! out, row 0 at the bottom as the format stores them. Verbatim and
//! run-length encoded storage, one or two bytes per channel value (two
//! are scaled to 0..=255, as `getrow` callers with byte buffers see them).

/// A decoded image: `channels[z][y * width + x]`.
pub struct Image {
    pub width: usize,
    pub height: usize,
    pub channels: Vec<Vec<u8>>,
}

fn be16(b: &[u8], at: usize) -> Option<usize> {
    Some(u16::from_be_bytes([*b.get(at)?, *b.get(at + 1)?]) as usize)
}

fn be32(b: &[u8], at: usize) -> Option<usize> {
    let s = b.get(at..at + 4)?;
    Some(u32::from_be_bytes([s[0], s[1], s[2], s[3]]) as usize)
}

/// Decodes `bytes`, or says why it is not an SGI image lsys reads.
pub fn decode(bytes: &[u8]) -> Result<Image, String> {
    let short = || "the file ends inside its header or data".to_string();
    if be16(bytes, 0) != Some(474) {
        return Err("it does not start with the SGI image magic number 474".into());
    }
    let rle = *bytes.get(2).ok_or_else(short)? == 1;
    let bpc = *bytes.get(3).ok_or_else(short)? as usize;
    if bpc != 1 && bpc != 2 {
        return Err(format!("{bpc} bytes per channel value (1 or 2 are read)"));
    }
    let dims = be16(bytes, 4).ok_or_else(short)?;
    let width = be16(bytes, 6).ok_or_else(short)?;
    let height = if dims >= 2 {
        be16(bytes, 8).ok_or_else(short)?
    } else {
        1
    };
    let depth = if dims >= 3 {
        be16(bytes, 10).ok_or_else(short)?
    } else {
        1
    };
    if width == 0 || height == 0 || depth == 0 || width * height * depth > 1 << 28 {
        return Err(format!("an image of {width} x {height} x {depth} values"));
    }
    let value = |at: usize| -> Option<u8> {
        if bpc == 1 {
            bytes.get(at).copied()
        } else {
            be16(bytes, at).map(|v| (v >> 8) as u8)
        }
    };
    let mut channels = vec![vec![0u8; width * height]; depth];
    for (z, channel) in channels.iter_mut().enumerate() {
        for y in 0..height {
            let row = &mut channel[y * width..(y + 1) * width];
            if !rle {
                let start = 512 + ((z * height + y) * width) * bpc;
                for (x, v) in row.iter_mut().enumerate() {
                    *v = value(start + x * bpc).ok_or_else(short)?;
                }
                continue;
            }
            let k = z * height + y;
            let mut at = be32(bytes, 512 + 4 * k).ok_or_else(short)?;
            let mut x = 0;
            loop {
                // The run header is a whole value (its low byte counts).
                let head = if bpc == 1 {
                    *bytes.get(at).ok_or_else(short)? as usize
                } else {
                    be16(bytes, at).ok_or_else(short)?
                };
                at += bpc;
                let count = head & 0x7f;
                if count == 0 {
                    break;
                }
                if x + count > width {
                    return Err(format!(
                        "row {y} of channel {z} runs past the image's width"
                    ));
                }
                if head & 0x80 != 0 {
                    for v in &mut row[x..x + count] {
                        *v = value(at).ok_or_else(short)?;
                        at += bpc;
                    }
                } else {
                    let v = value(at).ok_or_else(short)?;
                    at += bpc;
                    row[x..x + count].fill(v);
                }
                x += count;
            }
        }
    }
    Ok(Image {
        width,
        height,
        channels,
    })
}
