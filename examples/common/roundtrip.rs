//! What the drawing round trips share (`drawing_roundtrip.rs`,
//! `pailou_roundtrip.rs`): a seeded generator, the ink's box, the damage
//! a drawing is read after (gaps, jitter, blur, as `tests/infer.rs` damages
//! its drawings), a picture as PNG bytes, the reading `lsys infer` makes,
//! pixel masks for IoU, and the threads that measure every drawing.

// Each round trip uses part of this file.
#![allow(dead_code)]

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use lsys::driver::{infer_edited, read_drawing, InferFailure, InferOptions, Inference};
use lsys::internals::export::render::{write_png, Image};

/// `measure(k)` for every k in 0..n, on plain threads over a shared
/// counter: each drawing is independent and its result goes to its own
/// slot, so the report does not depend on the order they finish in.
/// Progress goes to stderr as `name: k/n drawings, s`.
pub fn measure_all<T: Send>(name: &str, n: usize, measure: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let started = Instant::now();
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get());
    let results: Mutex<Vec<Option<T>>> = Mutex::new((0..n).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                if k >= n {
                    break;
                }
                let r = measure(k);
                results.lock().expect("the results")[k] = Some(r);
                let d = done.fetch_add(1, Ordering::Relaxed) + 1;
                if d % 20 == 0 || d == n {
                    eprintln!(
                        "{name}: {d}/{n} drawings, {:.0} s",
                        started.elapsed().as_secs_f64()
                    );
                }
            });
        }
    });
    let results = results.into_inner().expect("the results");
    results
        .into_iter()
        .map(|r| r.expect("every drawing measured"))
        .collect()
}

/// `lsys infer`'s reading of a picture's PNG or SVG `bytes` (the driver's,
/// with its defaults), or why it gave none.
pub fn read(bytes: &[u8], name: &str) -> Result<Inference, String> {
    let why = |e: InferFailure| match e {
        InferFailure::Drawing(e) => e.to_string(),
        other => format!("{other:?}"),
    };
    let ink = read_drawing(bytes, name).map_err(why)?;
    infer_edited(&ink, name, &[], &[], &InferOptions::default()).map_err(why)
}

/// A pixel mask of the picture.
pub struct Mask {
    pub w: usize,
    pub h: usize,
    pub on: Vec<bool>,
}

impl Mask {
    pub fn new(w: usize, h: usize) -> Mask {
        Mask {
            w,
            h,
            on: vec![false; w * h],
        }
    }
    /// Marks the pixels whose centres lie in `[x0, x1) x [y0, y1)`.
    pub fn add(&mut self, b: [f64; 4]) {
        let span = |lo: f64, hi: f64, n: usize| {
            let a = (lo - 0.5).ceil().clamp(0.0, n as f64) as usize;
            let z = (hi - 0.5).ceil().clamp(0.0, n as f64) as usize;
            a..z.max(a)
        };
        for y in span(b[1], b[3], self.h) {
            for x in span(b[0], b[2], self.w) {
                self.on[y * self.w + x] = true;
            }
        }
    }
    /// Intersection over union; `None` when both are empty.
    pub fn iou(&self, other: &Mask) -> Option<f64> {
        let (mut both, mut any) = (0usize, 0usize);
        for (a, b) in self.on.iter().zip(&other.on) {
            both += usize::from(*a && *b);
            any += usize::from(*a || *b);
        }
        (any > 0).then(|| both as f64 / any as f64)
    }
}

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
