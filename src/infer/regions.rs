//! Regions: an [`Ink`] bitmap -> the closed areas between its lines, each
//! with its bounding box and area, the outside removed.
//!
//! Before the areas are found the drawing is cleaned as seed 003's Section 5
//! asks: specks of ink too small to be a line are erased, and the lines are
//! thickened by `gap` pixels so that breaks up to twice that (a scan's
//! dropped pixels, a pen lifted early) close. Boxes are grown back by the
//! same amount, so they reach the middle of the lines around them.

use super::drawing::Ink;

/// A closed area of the drawing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// `[x0, y0, x1, y1)` in pixels, y down.
    pub bbox: [i32; 4],
    /// Pixels inside, before the lines were thickened back.
    pub area: u32,
}

impl Region {
    pub fn w(&self) -> i32 {
        self.bbox[2] - self.bbox[0]
    }
    pub fn h(&self) -> i32 {
        self.bbox[3] - self.bbox[1]
    }
}

/// Ink specks of at most this many pixels are noise.
const SPECK: usize = 4;
/// Areas of fewer pixels than this (after thickening) are ignored: the
/// slivers between doubled lines.
const MIN_AREA: u32 = 6;

/// A drawing's paper, cleaned once: its closed areas and its outside.
#[derive(Clone, Debug)]
pub struct Paper {
    pub regions: Vec<Region>,
    /// The paper reachable from the picture's border without crossing a
    /// line, one flag per pixel (a Pailou's passages are outside).
    pub outside: Vec<bool>,
}

/// The paper of `ink`, lines thickened by `gap` pixels (0 to 8).
pub fn paper(ink: &Ink, gap: usize) -> Paper {
    let thick = thicken(&erase_specks(ink, gap), gap);
    Paper {
        regions: label(&thick, gap as i32),
        outside: outside(&thick),
    }
}

/// The regions of `ink`, lines thickened by `gap` pixels (0 to 8).
pub fn regions(ink: &Ink, gap: usize) -> Vec<Region> {
    let thick = thicken(&erase_specks(ink, gap), gap);
    label(&thick, gap as i32)
}

/// Removes 8-connected ink components of at most [`SPECK`] pixels that
/// stand alone: a piece of a line left between two breaks (a scan's gaps
/// right beside a junction) has other ink within a bridgeable break
/// (`2 gap + 1` pixels) and is kept, or erasing it would make one break of
/// the two, too wide to bridge.
fn erase_specks(ink: &Ink, gap: usize) -> Ink {
    let (w, h) = (ink.width, ink.height);
    let mut out = ink.clone();
    let mut seen = vec![false; w * h];
    let mut stack = Vec::new();
    let mut component = Vec::new();
    for start in 0..w * h {
        if !ink.ink[start] || seen[start] {
            continue;
        }
        component.clear();
        stack.push(start);
        seen[start] = true;
        while let Some(i) = stack.pop() {
            component.push(i);
            let (x, y) = ((i % w) as i64, (i / w) as i64);
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                        continue;
                    }
                    let j = ny as usize * w + nx as usize;
                    if ink.ink[j] && !seen[j] {
                        seen[j] = true;
                        stack.push(j);
                    }
                }
            }
        }
        if component.len() <= SPECK && alone(ink, &component, 2 * gap as i64 + 1) {
            for &i in &component {
                out.ink[i] = false;
            }
        }
    }
    out
}

/// Whether no ink but `component`'s lies within `r` pixels of it.
fn alone(ink: &Ink, component: &[usize], r: i64) -> bool {
    let (w, h) = (ink.width as i64, ink.height as i64);
    component.iter().all(|&i| {
        let (x, y) = ((i as i64) % w, (i as i64) / w);
        (y - r..=y + r).all(|ny| {
            (x - r..=x + r).all(|nx| {
                let j = (ny * w + nx) as usize;
                nx < 0 || ny < 0 || nx >= w || ny >= h || !ink.ink[j] || component.contains(&j)
            })
        })
    })
}

/// Dilates the ink by a square of radius `r` (separably: rows, then columns).
fn thicken(ink: &Ink, r: usize) -> Ink {
    if r == 0 {
        return ink.clone();
    }
    let (w, h) = (ink.width, ink.height);
    let mut rows = vec![false; w * h];
    for y in 0..h {
        let line = &ink.ink[y * w..(y + 1) * w];
        // Distance to the last ink seen, left to right then right to left.
        let mut last = usize::MAX / 2;
        for x in 0..w {
            if line[x] {
                last = x;
            }
            rows[y * w + x] = x.saturating_sub(last) <= r && last <= x;
        }
        let mut next = usize::MAX / 2;
        for x in (0..w).rev() {
            if line[x] {
                next = x;
            }
            if next >= x && next - x <= r {
                rows[y * w + x] = true;
            }
        }
    }
    let mut out = vec![false; w * h];
    for x in 0..w {
        let mut last = usize::MAX / 2;
        for y in 0..h {
            if rows[y * w + x] {
                last = y;
            }
            out[y * w + x] = last <= y && y - last <= r;
        }
        let mut next = usize::MAX / 2;
        for y in (0..h).rev() {
            if rows[y * w + x] {
                next = y;
            }
            if next >= y && next - y <= r {
                out[y * w + x] = true;
            }
        }
    }
    Ink {
        width: w,
        height: h,
        ink: out,
    }
}

/// 4-connected areas of paper that do not touch the picture's border.
fn label(ink: &Ink, grow: i32) -> Vec<Region> {
    let (w, h) = (ink.width, ink.height);
    let mut seen = vec![false; w * h];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for start in 0..w * h {
        if ink.ink[start] || seen[start] {
            continue;
        }
        let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0, 0);
        let mut area = 0u32;
        let mut outside = false;
        seen[start] = true;
        stack.push(start);
        while let Some(i) = stack.pop() {
            let (x, y) = (i % w, i / w);
            area += 1;
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x + 1), y1.max(y + 1));
            if x == 0 || y == 0 || x + 1 == w || y + 1 == h {
                outside = true;
            }
            let mut visit = |j: usize| {
                if !ink.ink[j] && !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            };
            if x > 0 {
                visit(i - 1);
            }
            if x + 1 < w {
                visit(i + 1);
            }
            if y > 0 {
                visit(i - w);
            }
            if y + 1 < h {
                visit(i + w);
            }
        }
        if outside || area < MIN_AREA {
            continue;
        }
        out.push(Region {
            bbox: [
                x0 as i32 - grow,
                y0 as i32 - grow,
                x1 as i32 + grow,
                y1 as i32 + grow,
            ],
            area,
        });
    }
    out
}

/// The paper reachable from the picture's border without crossing a line
/// of `ink` (4-connected), one flag per pixel.
fn outside(ink: &Ink) -> Vec<bool> {
    let (w, h) = (ink.width, ink.height);
    let mut out = vec![false; w * h];
    let mut stack: Vec<usize> = (0..w * h)
        .filter(|&i| {
            let (x, y) = (i % w, i / w);
            (x == 0 || y == 0 || x + 1 == w || y + 1 == h) && !ink.ink[i]
        })
        .collect();
    for &i in &stack {
        out[i] = true;
    }
    while let Some(i) = stack.pop() {
        let (x, y) = (i % w, i / w);
        let near = [
            (x > 0).then(|| i - 1),
            (x + 1 < w).then(|| i + 1),
            (y > 0).then(|| i - w),
            (y + 1 < h).then(|| i + w),
        ];
        for j in near.into_iter().flatten() {
            if !ink.ink[j] && !out[j] {
                out[j] = true;
                stack.push(j);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn draw(w: usize, h: usize, rects: &[[usize; 4]]) -> Ink {
        let mut ink = Ink {
            width: w,
            height: h,
            ink: vec![false; w * h],
        };
        for &[x0, y0, x1, y1] in rects {
            for x in x0..=x1 {
                ink.ink[y0 * w + x] = true;
                ink.ink[y1 * w + x] = true;
            }
            for y in y0..=y1 {
                ink.ink[y * w + x0] = true;
                ink.ink[y * w + x1] = true;
            }
        }
        ink
    }

    #[test]
    fn two_rectangles_are_two_regions_and_the_outside_is_none() {
        let ink = draw(60, 40, &[[5, 5, 25, 30], [30, 5, 50, 30]]);
        let r = regions(&ink, 1);
        assert_eq!(r.len(), 2, "{r:?}");
        // The inside of the outline, up to the lines.
        assert_eq!(r[0].bbox, [6, 6, 25, 30]);
    }

    #[test]
    fn a_gap_of_three_pixels_closes_with_gap_two_but_not_zero() {
        let mut ink = draw(60, 40, &[[5, 5, 50, 30]]);
        for x in 20..23 {
            ink.ink[5 * 60 + x] = false;
        }
        assert_eq!(regions(&ink, 0).len(), 0);
        assert_eq!(regions(&ink, 2).len(), 1);
    }

    #[test]
    fn specks_inside_a_region_do_not_split_it() {
        let mut ink = draw(60, 40, &[[5, 5, 50, 30]]);
        ink.ink[15 * 60 + 20] = true;
        ink.ink[15 * 60 + 21] = true;
        let r = regions(&ink, 1);
        assert_eq!(r.len(), 1);
        assert!(!thicken(&erase_specks(&ink, 1), 0).ink[15 * 60 + 20]);
    }

    #[test]
    fn a_piece_of_line_between_two_breaks_is_not_a_speck() {
        // The left side broken at rows 8..11 and 14..17, and the top
        // beside the corner: the piece at rows 11..14 is three pixels.
        let mut ink = draw(60, 40, &[[5, 5, 50, 30]]);
        for y in (8..11).chain(14..17) {
            ink.ink[y * 60 + 5] = false;
        }
        for x in 4..8 {
            ink.ink[5 * 60 + x] = false;
        }
        assert!(erase_specks(&ink, 2).ink[12 * 60 + 5]);
        assert_eq!(regions(&ink, 2).len(), 1);
        // Erased, the break would be 9 pixels, past what gap 2 bridges.
        assert!(!erase_specks(&ink, 0).ink[12 * 60 + 5]);
    }
}
