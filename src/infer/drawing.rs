//! Reading a drawing: PNG or SVG bytes -> an [`Ink`] bitmap (true where a
//! line is drawn), after checking that the picture is a line drawing at all.
//! An SVG is rasterised (resvg) at its own size, scaled up by a whole
//! factor to at least [`SVG_MIN_WIDTH`] pixels across so that its thin
//! lines and small parts survive gap bridging; text is ignored.
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
        return Err(unreadable("it is not a PNG image".to_string()));
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

/// SVG drawings narrower than this are scaled up by a whole factor.
pub const SVG_MIN_WIDTH: f32 = 1000.0;

/// Whether `bytes` look like SVG (or other XML) rather than a PNG.
pub fn is_svg(bytes: &[u8]) -> bool {
    let text = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(bytes);
    text.trim_ascii_start().starts_with(b"<")
}

/// Rasterises the SVG `bytes` and separates ink from paper.
pub fn read_svg(bytes: &[u8], path: &str) -> Result<Ink, InferError> {
    use resvg::{tiny_skia, usvg};
    let unreadable = |reason: String| InferError::Unreadable {
        path: path.to_string(),
        reason,
    };
    let tree = usvg::Tree::from_data(bytes, &usvg::Options::default())
        .map_err(|e| unreadable(format!("not a readable SVG: {e}")))?;
    let size = tree.size();
    let k = (SVG_MIN_WIDTH / size.width()).ceil().max(1.0);
    let (w, h) = ((size.width() * k).ceil(), (size.height() * k).ceil());
    let too_big = || InferError::TooBig {
        path: path.to_string(),
        width: w.min(u32::MAX as f32) as u32,
        height: h.min(u32::MAX as f32) as u32,
    };
    if !(w <= MAX_SIDE as f32
        && h <= MAX_SIDE as f32
        && (w as f64) * (h as f64) <= MAX_PIXELS as f64)
    {
        return Err(too_big());
    }
    let mut pixmap = tiny_skia::Pixmap::new(w as u32, h as u32).ok_or_else(too_big)?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(k, k),
        &mut pixmap.as_mut(),
    );
    // Opaque after the white fill, so the premultiplied colour is the colour.
    let grey: Vec<u8> = pixmap
        .data()
        .chunks_exact(4)
        .map(|p| luma(p).round() as u8)
        .collect();
    binarize(&grey, w as usize, h as usize, path)
}

/// Width of a separator stroke drawn by hand, in pixels: a drawn line's,
/// closing a region as a line of the drawing would.
pub const STROKE_WIDTH: f32 = 3.0;

/// Separator strokes drawn as polylines in the drawing's pixels (the
/// studio's drawing page) -> an ink picture `width` x `height` holding
/// them, for [`super::add_strokes`]. Points outside the picture are
/// clipped; a polyline of one point is a dot.
pub fn stroke_lines(width: usize, height: usize, lines: &[Vec<[f32; 2]>]) -> Ink {
    use resvg::tiny_skia::{LineCap, Paint, PathBuilder, Pixmap, Stroke, Transform};
    let mut ink = Ink {
        width,
        height,
        ink: vec![false; width * height],
    };
    let Some(mut pixmap) = Pixmap::new(width as u32, height as u32) else {
        return ink;
    };
    let paint = Paint {
        anti_alias: false,
        ..Paint::default()
    };
    let stroke = Stroke {
        width: STROKE_WIDTH,
        line_cap: LineCap::Round,
        ..Stroke::default()
    };
    for line in lines.iter().filter(|l| !l.is_empty()) {
        let finite = |p: &[f32; 2]| p[0].is_finite() && p[1].is_finite();
        let mut pb = PathBuilder::new();
        let mut points = line.iter().filter(|p| finite(p));
        let Some(first) = points.next() else { continue };
        pb.move_to(first[0], first[1]);
        let mut drawn = false;
        for p in points {
            pb.line_to(p[0], p[1]);
            drawn = true;
        }
        if !drawn {
            // A dot: a segment of no length draws nothing.
            pb.line_to(first[0] + 0.01, first[1]);
        }
        if let Some(path) = pb.finish() {
            pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
        }
    }
    for (i, p) in pixmap.pixels().iter().enumerate() {
        ink.ink[i] = p.alpha() > 0;
    }
    ink
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
