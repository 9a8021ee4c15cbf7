//! Reading a drawing: PNG bytes -> an [`Ink`] bitmap (true where a line is
//! drawn), after checking that the picture is a line drawing at all.
//!
//! The threshold between ink and paper is Otsu's (the split of the grey
//! histogram with the largest between-class variance), so that scans with a
//! grey paper and soft pencil read as well as pure black on white.

use super::error::{InferError, MAX_PIXELS, MAX_SIDE};

/// A binary picture, row by row from the top.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Ink {
    pub width: usize,
    pub height: usize,
    pub ink: Vec<bool>,
}

impl Ink {
    pub fn at(&self, x: usize, y: usize) -> bool {
        self.ink[y * self.width + x]
    }
}

/// More ink than this fraction of the picture is a filled picture.
const MAX_INK: f64 = 0.45;
/// More than this fraction of mid-grey pixels is a photograph.
const MAX_MIDTONES: f64 = 0.35;

/// Decodes `bytes` (PNG) and separates ink from paper. `path` names the
/// drawing in messages.
pub fn read_png(bytes: &[u8], path: &str) -> Result<Ink, InferError> {
    let unreadable = |reason: String| InferError::Unreadable {
        path: path.to_string(),
        reason,
    };
    if !bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        let reason = if bytes.trim_ascii_start().starts_with(b"<") {
            "it looks like SVG or XML; export the drawing as PNG".to_string()
        } else {
            "it is not a PNG image".to_string()
        };
        return Err(unreadable(reason));
    }
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().map_err(|e| unreadable(e.to_string()))?;
    let (width, height) = {
        let info = reader.info();
        (info.width, info.height)
    };
    if width > MAX_SIDE || height > MAX_SIDE || width as u64 * height as u64 > MAX_PIXELS {
        return Err(InferError::TooBig {
            path: path.to_string(),
            width,
            height,
        });
    }
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| unreadable("its decoded size does not fit in memory".to_string()))?;
    let mut buf = vec![0; size];
    let frame = reader
        .next_frame(&mut buf)
        .map_err(|e| unreadable(e.to_string()))?;
    let channels = frame.color_type.samples();
    let grey: Vec<u8> = buf[..frame.buffer_size()]
        .chunks_exact(channels)
        .map(|p| {
            let (luma, alpha) = match p.len() {
                1 => (p[0] as f32, 255.0),
                2 => (p[0] as f32, p[1] as f32),
                3 => (luma(p), 255.0),
                _ => (luma(p), p[3] as f32),
            };
            // Transparent pixels are paper.
            let a = alpha / 255.0;
            (luma * a + 255.0 * (1.0 - a)).round() as u8
        })
        .collect();
    binarize(&grey, width as usize, height as usize, path)
}

fn luma(p: &[u8]) -> f32 {
    0.2126 * p[0] as f32 + 0.7152 * p[1] as f32 + 0.0722 * p[2] as f32
}

/// Grey levels -> ink, with the checks that it is a line drawing.
pub fn binarize(grey: &[u8], width: usize, height: usize, path: &str) -> Result<Ink, InferError> {
    let not_lines = |reason: String| InferError::NotALineDrawing {
        path: path.to_string(),
        reason,
    };
    let n = grey.len().max(1) as f64;
    let mut histogram = [0u64; 256];
    for &g in grey {
        histogram[g as usize] += 1;
    }
    let midtones = histogram[64..192].iter().sum::<u64>() as f64 / n;
    if midtones > MAX_MIDTONES {
        return Err(not_lines(format!(
            "{:.0} % of it is mid-grey, as in a photograph or a shaded picture",
            midtones * 100.0
        )));
    }
    let threshold = otsu(&histogram).clamp(48, 208);
    let ink: Vec<bool> = grey.iter().map(|&g| g < threshold).collect();
    let inked = ink.iter().filter(|&&b| b).count() as f64 / n;
    if inked == 0.0 {
        return Err(not_lines("it is blank".to_string()));
    }
    if inked > MAX_INK {
        return Err(not_lines(format!(
            "{:.0} % of it is dark, so it is a filled picture or dark lines on light ones",
            inked * 100.0
        )));
    }
    Ok(Ink { width, height, ink })
}

/// Otsu's threshold: grey levels below it are ink.
fn otsu(histogram: &[u64; 256]) -> u8 {
    let total: u64 = histogram.iter().sum();
    let sum: f64 = histogram
        .iter()
        .enumerate()
        .map(|(g, &c)| g as f64 * c as f64)
        .sum();
    let (mut below, mut sum_below) = (0u64, 0.0f64);
    let (mut best, mut best_t) = (-1.0f64, 128u8);
    for (t, &count) in histogram.iter().enumerate() {
        // `t` is the first level counted as paper.
        if below > 0 && below < total {
            let (wb, wf) = (below as f64, (total - below) as f64);
            let (mb, mf) = (sum_below / wb, (sum - sum_below) / wf);
            let between = wb * wf * (mb - mf) * (mb - mf);
            if between > best {
                best = between;
                best_t = t as u8;
            }
        }
        below += count;
        sum_below += t as f64 * count as f64;
    }
    best_t
}
