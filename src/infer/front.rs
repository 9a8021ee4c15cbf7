//! What a front is: a drawing's ink -> whether it is a Pailou's front
//! (pillars standing free on the ground, the passages between them open
//! to the sky) rather than a hall's, and where its ground pillars stand.
//!
//! A hall's front is closed from column to column: walls, doors and
//! windows fill its bays, so a row through its body is drawn from end to
//! end. A Pailou's passages are the drawing's outside: a row through the
//! lower part of its pillars crosses each pillar (its two outlines and the
//! paper between them) and, between two pillars, nothing. The row is one
//! of the lower part's with the most runs over a stretch of rows: a low
//! lintel or board crossing some rows joins pillars (fewer runs), and a
//! row crossing the bases has as many.

use super::drawing::Ink;
use super::regions::Region;

/// The rows looked at: from this part of the ink's height above its
/// bottom (bases are separate runs too) ...
const FROM: f64 = 0.04;
/// ... to this part (under the lowest lintels of an 8-7-x).
const TO: f64 = 0.3;
/// A run count holds over at least this part of the height to count.
const STRETCH: f64 = 0.02;
/// Two pillars stand at least this many of their widths apart.
const PASSAGE: usize = 2;

/// A Pailou front's ground pillars, left to right.
#[derive(Clone, Debug, PartialEq)]
pub struct PailouFront {
    /// Each pillar's extent across the row read, `[x0, x1)` in pixels.
    pub pillars: Vec<[usize; 2]>,
    /// The row read (pixels, y down).
    pub row: usize,
    /// The passage between each two pillars, left to right, `[x0, y0, x1,
    /// y1)`: from one pillar to the next, and from the first line above
    /// the row read (at the passage's middle) down to the ink's bottom.
    pub passages: Vec<[usize; 4]>,
}

/// The Pailou front drawn in `ink` (`outside`: its outside, per pixel), or
/// `None` for a hall or anything else: an even number of pillars, at least
/// two (the Pailou is symmetric and its centre is an entrance), mirrored
/// about the ink's middle within a pillar's width, several widths apart.
pub fn pailou_front(ink: &Ink, outside: &[bool]) -> Option<PailouFront> {
    let (w, h) = (ink.width, ink.height);
    let rows_with_ink: Vec<usize> = (0..h)
        .filter(|&y| ink.ink[y * w..(y + 1) * w].iter().any(|&i| i))
        .collect();
    let (top, bottom) = (*rows_with_ink.first()?, *rows_with_ink.last()?);
    let height = (bottom - top) as f64;
    let lo = bottom.saturating_sub((TO * height) as usize);
    let hi = bottom.saturating_sub((FROM * height) as usize);
    // Each row's runs of drawn-or-enclosed paper.
    let runs = |y: usize| -> Vec<[usize; 2]> {
        let line = &outside[y * w..(y + 1) * w];
        let mut out = Vec::new();
        let mut start = None;
        for (x, &o) in line.iter().chain(std::iter::once(&true)).enumerate() {
            match (o, start) {
                (false, None) => start = Some(x),
                (true, Some(s)) => {
                    out.push([s, x]);
                    start = None;
                }
                _ => {}
            }
        }
        out
    };
    // Of the rows with that many runs, the one whose runs are narrowest
    // (the shafts, not the bases).
    let counts: Vec<(usize, usize, usize)> = (lo..=hi)
        .map(|y| {
            let r = runs(y);
            (y, r.len(), r.iter().map(|p| p[1] - p[0]).sum())
        })
        .collect();
    // The most runs a stretch of rows holds: lintels and boards crossing
    // some rows join pillars into fewer runs, never more.
    let stretch = ((STRETCH * height) as usize).max(3);
    let n = counts
        .chunk_by(|a, b| a.1 == b.1)
        .filter(|run| run.len() >= stretch)
        .map(|run| run[0].1)
        .max()?;
    let row = counts
        .iter()
        .filter(|c| c.1 == n)
        .min_by_key(|c| (c.2, c.0))?
        .0;
    let pillars = runs(row);
    if pillars.len() < 2 || pillars.len() % 2 != 0 {
        return None;
    }
    let width = |p: &[usize; 2]| p[1] - p[0];
    let (x0, x1) = (pillars[0][0], pillars[pillars.len() - 1][1]);
    for k in 0..pillars.len() / 2 {
        let (l, r) = (&pillars[k], &pillars[pillars.len() - 1 - k]);
        let off = (l[0] + l[1] + r[0] + r[1]) as i64 - 2 * (x0 + x1) as i64;
        if off.unsigned_abs() as usize > 2 * width(l).max(width(r)).max(4) {
            return None;
        }
    }
    for pair in pillars.windows(2) {
        if pair[1][0] - pair[0][1] < PASSAGE * width(&pair[0]).max(width(&pair[1])) {
            return None;
        }
    }
    let passages = pillars
        .windows(2)
        .map(|pair| {
            let x = (pair[0][1] + pair[1][0]) / 2;
            let mut top = row;
            while top > 0 && outside[(top - 1) * w + x] {
                top -= 1;
            }
            [pair[0][1], top, pair[1][0], bottom + 1]
        })
        .collect();
    Some(PailouFront {
        pillars,
        row,
        passages,
    })
}

/// A line across the bottom of the drawing under a Pailou's pillars (the
/// ground, as an architect draws it) closes the passages, so that they are
/// not the outside and [`pailou_front`] sees a hall. When two closed areas
/// at least stand on the ink's bottom (within `gap` and two pixels), each
/// a quarter of the ink's height or taller and plain (their area 0.7 of
/// their box: an open passage, not a bay with a door in it, which stands
/// on a platform above the ground), this is `ink` with that line erased:
/// in each of the bottom rows up to twice the pen's reach, every run of
/// ink 0.6 of the ink's width or longer. `None` otherwise (a hall: its
/// doors stand on the platform, not on the drawing's bottom).
pub fn without_ground_line(ink: &Ink, regions: &[Region], gap: usize) -> Option<Ink> {
    let (w, h) = (ink.width, ink.height);
    let rows: Vec<usize> = (0..h)
        .filter(|&y| ink.ink[y * w..(y + 1) * w].iter().any(|&i| i))
        .collect();
    let (top, bottom) = (*rows.first()?, *rows.last()?);
    let (height, reach) = ((bottom - top) as f64, gap as i32 + 2);
    let passages = regions
        .iter()
        .filter(|r| {
            let box_area = (r.w().max(0) * r.h().max(0)) as f64;
            bottom as i32 + 1 - r.bbox[3] <= reach + 2 * gap as i32 + 4
                && f64::from(r.h()) >= 0.25 * height
                && f64::from(r.area) >= 0.7 * box_area
        })
        .count();
    if passages < 2 {
        return None;
    }
    let span = (0..w)
        .filter(|&x| (top..=bottom).any(|y| ink.at(x, y)))
        .count();
    let long = (0.6 * span as f64) as usize;
    let mut open = ink.clone();
    let mut erased = false;
    for y in bottom.saturating_sub(2 * reach as usize + 4)..=bottom {
        let row = &mut open.ink[y * w..(y + 1) * w];
        let mut x = 0;
        while x < w {
            if !row[x] {
                x += 1;
                continue;
            }
            let start = x;
            while x < w && row[x] {
                x += 1;
            }
            if x - start >= long {
                row[start..x].fill(false);
                erased = true;
            }
        }
    }
    erased.then_some(open)
}
