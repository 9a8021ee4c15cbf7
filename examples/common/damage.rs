//! What the drawing round trips share (`drawing_roundtrip.rs`,
//! `pailou_roundtrip.rs`): a seeded generator, the ink's box, the damage
//! a drawing is read after (gaps, jitter, blur, as `tests/infer.rs` damages
//! its drawings), and a picture as PNG bytes.

// Each round trip uses part of this file.
#![allow(dead_code)]

use lsys::internals::export::render::{write_png, Image};

/// splitmix64: small, seeded, the same on every machine.
pub struct SplitMix(pub u64);

impl SplitMix {
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The box around the ink, `[x0, y0, x1, y1)`.
pub fn ink_box(img: &Image) -> Option<[i32; 4]> {
    let (w, h) = (img.width as usize, img.height as usize);
    let mut b = [i32::MAX, i32::MAX, i32::MIN, i32::MIN];
    for y in 0..h {
        for x in 0..w {
            if img.rgb[(y * w + x) * 3] < 128 {
                b = [
                    b[0].min(x as i32),
                    b[1].min(y as i32),
                    b[2].max(x as i32 + 1),
                    b[3].max(y as i32 + 1),
                ];
            }
        }
    }
    (b[0] <= b[2]).then_some(b)
}

/// How a drawing is read: as drawn, or damaged as `tests/infer.rs` damages
/// its W=24 drawing.
pub const CONDITIONS: [&str; 4] = ["clean", "gaps", "jitter", "blur"];

pub fn damaged(img: &Image, condition: &str, seed: u64) -> Image {
    let (w, h) = (img.width as usize, img.height as usize);
    let buf = &img.rgb;
    let ink = |x: usize, y: usize| buf[(y * w + x) * 3] < 128;
    let mut out = vec![255u8; w * h * 3];
    match condition {
        "gaps" => {
            // 3 pixels of every 40 along a line erased across it.
            for y in 1..h - 1 {
                for x in 1..w - 1 {
                    if !ink(x, y) {
                        continue;
                    }
                    let along_x = ink(x - 1, y) && ink(x + 1, y);
                    let along_y = ink(x, y - 1) && ink(x, y + 1);
                    if !((along_x && x % 40 < 3) || (along_y && y % 40 < 3)) {
                        out[(y * w + x) * 3..(y * w + x) * 3 + 3].fill(0);
                    }
                }
            }
        }
        "jitter" => {
            // Each stretch of 8 rows (columns) shifted a pixel its own
            // way, as a shaky hand or a scan.
            let mut rng = SplitMix(seed);
            let shift: Vec<i64> = (0..h / 8 + w / 8 + 2)
                .map(|_| (rng.next() % 3) as i64 - 1)
                .collect();
            for y in 1..h - 1 {
                for x in 1..w - 1 {
                    if ink(x, y) {
                        let (dx, dy) = (shift[y / 8], shift[h / 8 + 1 + x / 8]);
                        let (nx, ny) = ((x as i64 + dx) as usize, (y as i64 + dy) as usize);
                        out[(ny * w + nx) * 3..(ny * w + nx) * 3 + 3].fill(0);
                    }
                }
            }
        }
        "blur" => {
            // Each pixel the mean of its 3 x 3 neighbourhood.
            for y in 1..h - 1 {
                for x in 1..w - 1 {
                    let sum: u32 = (0..9)
                        .map(|k| buf[((y + k / 3 - 1) * w + x + k % 3 - 1) * 3] as u32)
                        .sum();
                    out[(y * w + x) * 3..(y * w + x) * 3 + 3].fill((sum / 9) as u8);
                }
            }
        }
        _ => out.clone_from(buf),
    }
    Image {
        width: img.width,
        height: img.height,
        rgb: out,
    }
}

pub fn png_bytes(img: &Image) -> Vec<u8> {
    let mut bytes = Vec::new();
    write_png(img, &mut bytes).expect("PNG into memory");
    bytes
}
