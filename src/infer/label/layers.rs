//! The bracket and rafter layers: a band between the body and the roof
//! -> its pieces labelled, each drawn element one leaf, the layer's back
//! `other`. Sets drawn as stacked parts, quartered blocks, plain outlines
//! or hanging arms are each read here (see `docs/drawing.md`).

use super::super::regions::Region;
use super::super::tree::{Axis, Node};
use super::{collapse, is_plain, placeholder};

/// A bracket or rafter layer: each piece with something drawn is one
/// element; the others are the layer's back.
pub(super) fn row_of(band: &mut Node, kind: &'static str, regions: &[Region]) {
    band.label = "other";
    // A layer narrower than the band (the bracket layer under a wider
    // roof) is the one drawn piece between two empty margins.
    let mut band = band;
    while band.split.is_some()
        && band
            .children
            .iter()
            .filter(|c| !c.regions.is_empty())
            .count()
            == 1
        && band.children.len() > 1
    {
        for c in &mut band.children {
            if c.regions.is_empty() {
                collapse(c, "other");
            }
        }
        let inner = band.children.iter().position(|c| !c.regions.is_empty());
        match inner {
            Some(i) => band = &mut band.children[i],
            None => break,
        }
        band.label = "other";
    }
    // A layer that goes round the corners: at each end of the front's
    // row, a side face's first element seen end-on, cut off from the
    // row by a line of its own. Those ends are elements; the row is the
    // one drawn piece wider than half the band, read as a layer itself.
    if band.split == Some(Axis::X) {
        let drawn = |c: &Node| !c.regions.is_empty();
        let wide: Vec<usize> = (0..band.children.len())
            .filter(|&k| drawn(&band.children[k]) && band.children[k].w() * 2 > band.w())
            .collect();
        let ends = band.children.iter().filter(|c| drawn(c)).count() - wide.len();
        if wide.len() == 1 && (1..=2).contains(&ends) {
            for (k, c) in band.children.iter_mut().enumerate() {
                if k != wide[0] {
                    let label = if drawn(c) { kind } else { "other" };
                    collapse(c, label);
                }
            }
            row_of(&mut band.children[wide[0]], kind, regions);
            return;
        }
    }
    if band.split == Some(Axis::Y) {
        // Elements drawn as stacked parts (a bracket set's arm over its
        // block) are cut into rows first: take the layer by columns.
        by_columns(band, regions);
    }
    if band.split != Some(Axis::X) {
        if band.content().next().is_some() {
            collapse(band, kind);
        }
        return;
    }
    // Corner sets: a side face's first set seen end-on at each end of the
    // row, narrow, with a narrow piece of back beside it (the front row's
    // margin). The sets are set aside (their regions hidden from the rules
    // below) and are sets; the margins are back.
    let (corners, margins) = if kind == "bracket" {
        corner_sets(band)
    } else {
        Default::default()
    };
    for k in margins {
        let c = &mut band.children[k];
        c.regions.clear();
        c.fills.clear();
    }
    // Kept by box: merging detailed runs below renumbers the pieces.
    let hidden: Vec<([i32; 4], Vec<usize>)> = corners
        .iter()
        .map(|&k| {
            let c = &mut band.children[k];
            (c.bbox, std::mem::take(&mut c.regions))
        })
        .collect();
    // When the bracket sets stand from the beam to the eave, the layer's
    // back between them is cut into closed pieces too: an unbroken run of
    // an odd number of drawn pieces alternates sets and back. Which are
    // the sets: the run's end pieces are margins of back when they are
    // not as wide as the others of their parity (a margin is whatever was
    // left at the layer's end), sets otherwise (sets repeat exactly).
    // (Rafters are left alone.)
    let drawn: Vec<usize> = (0..band.children.len())
        .filter(|&k| !band.children[k].regions.is_empty())
        .collect();
    let unbroken = drawn.windows(2).all(|w| w[1] == w[0] + 1);
    let mut alternate = None;
    if kind == "bracket" && unbroken && drawn.len() >= 5 && drawn.len() % 2 == 1 {
        let even: Vec<i32> = drawn
            .iter()
            .step_by(2)
            .map(|&k| band.children[k].w())
            .collect();
        let mut inner = even[1..even.len() - 1].to_vec();
        inner.sort_unstable();
        let med = inner[inner.len() / 2] as f64;
        let off = |w: i32| (w as f64 - med).abs() > 0.2 * med + 1.0;
        let ends_are_back = off(even[0]) || off(even[even.len() - 1]);
        let back_parity = usize::from(!ends_are_back);
        let backs_plain = drawn
            .iter()
            .skip(back_parity)
            .step_by(2)
            .all(|&k| is_plain(&band.children[k], regions));
        if backs_plain {
            alternate = Some((drawn[0], back_parity));
        }
    }
    // Bracket sets drawn with inner lines (a block quartered by its arms)
    // are cut into several pieces, each with something drawn inside; the
    // back's pieces between them are plain: a run of adjacent detailed
    // pieces is one set.
    if kind == "bracket" && alternate.is_none() {
        merge_detailed_runs(band, regions);
    }
    // A drawn sliver under a third of the sets' median width is a piece of
    // back closed off by a line drawn close beside a set; inside the row
    // (not at its ends, where a corner set seen end-on is narrow too),
    // under half of it.
    let mut widths: Vec<i32> = band
        .children
        .iter()
        .filter(|c| !c.regions.is_empty())
        .map(|c| c.w())
        .collect();
    widths.sort_unstable();
    let median = widths.get(widths.len() / 2).copied().unwrap_or(0);
    let drawn_at: Vec<usize> = (0..band.children.len())
        .filter(|&k| !band.children[k].regions.is_empty())
        .collect();
    let inner = |k: usize| drawn_at.first() < Some(&k) && drawn_at.last() > Some(&k);
    let sliver = |k: usize, c: &Node| {
        let limit = if inner(k) { 2 } else { 3 };
        kind == "bracket" && c.w() * limit < median && is_plain(c, regions)
    };
    let mut n = 0;
    for (k, c) in band.children.iter_mut().enumerate() {
        let back =
            sliver(k, c) || alternate.is_some_and(|(f, parity)| k >= f && (k - f) % 2 == parity);
        if c.regions.is_empty() || back {
            collapse(c, "other");
            // The layer's back, not something left unrecognised.
            c.regions.clear();
            c.fills.clear();
        } else {
            collapse(c, kind);
            n += 1;
        }
    }
    for (bbox, regions) in hidden {
        if let Some(c) = band.children.iter_mut().find(|c| c.bbox == bbox) {
            c.regions = regions;
            collapse(c, kind);
            n += 1;
        }
    }
    band.repeat = n >= 3;
}

/// The two corner sets of a bracket row and the margins of back beside
/// them, if the row has them: at each end the first two drawn pieces are
/// adjacent and both under 0.8 of the median width of the pieces between.
fn corner_sets(band: &Node) -> (Vec<usize>, Vec<usize>) {
    let drawn: Vec<usize> = (0..band.children.len())
        .filter(|&k| !band.children[k].regions.is_empty())
        .collect();
    let n = drawn.len();
    if n < 7 {
        return Default::default();
    }
    let mut widths: Vec<i32> = drawn[2..n - 2]
        .iter()
        .map(|&k| band.children[k].w())
        .collect();
    widths.sort_unstable();
    let median = widths[widths.len() / 2] as f64;
    let narrow = |k: usize| (band.children[k].w() as f64) < 0.8 * median;
    let (a, b, y, z) = (drawn[0], drawn[1], drawn[n - 2], drawn[n - 1]);
    if b == a + 1 && z == y + 1 && [a, b, y, z].into_iter().all(narrow) {
        (vec![a, z], vec![b, y])
    } else {
        Default::default()
    }
}

/// In a layer with both plain and detailed drawn pieces, joins each run
/// of adjacent detailed pieces into one piece; the plain ones become
/// undrawn back.
fn merge_detailed_runs(band: &mut Node, regions: &[Region]) {
    let detailed: Vec<bool> = band
        .children
        .iter()
        .map(|c| !c.regions.is_empty() && !is_plain(c, regions))
        .collect();
    let plain_drawn = band
        .children
        .iter()
        .zip(&detailed)
        .any(|(c, &d)| !d && !c.regions.is_empty());
    if !plain_drawn || !detailed.windows(2).any(|w| w[0] && w[1]) {
        return;
    }
    let mut out: Vec<Node> = Vec::new();
    let mut last_detailed = false;
    for (c, d) in std::mem::take(&mut band.children).into_iter().zip(detailed) {
        match out.last_mut() {
            Some(prev) if d && last_detailed => {
                prev.bbox[2] = c.bbox[2];
                prev.regions.extend(c.regions);
                prev.children.clear();
                prev.split = None;
                prev.fills.clear();
            }
            _ if d => out.push(c),
            _ => out.push(Node {
                bbox: c.bbox,
                ..placeholder()
            }),
        }
        last_detailed = d;
    }
    band.children = out;
}

/// Re-cuts `band` along x where no region drawn in it (other than those
/// filling it, the layer's back) crosses: each cluster of region boxes
/// projected on x is one piece, and the strips between them are pieces
/// with nothing drawn.
fn by_columns(band: &mut Node, regions: &[Region]) {
    let mut spans: Vec<(i32, i32, usize)> = band
        .content()
        .map(|r| (regions[r].bbox[0], regions[r].bbox[2], r))
        .collect();
    if spans.is_empty() {
        return;
    }
    spans.sort_unstable();
    let [x0, y0, x1, y1] = band.bbox;
    let mut pieces: Vec<Node> = Vec::new();
    let mut at = x0;
    let mut k = 0;
    while k < spans.len() {
        let (lo, mut hi, _) = spans[k];
        let mut members = Vec::new();
        while k < spans.len() && spans[k].0 <= hi {
            hi = hi.max(spans[k].1);
            members.push(spans[k].2);
            k += 1;
        }
        if lo > at {
            pieces.push(Node {
                bbox: [at, y0, lo, y1],
                ..placeholder()
            });
        }
        pieces.push(Node {
            bbox: [lo, y0, hi, y1],
            regions: members,
            ..placeholder()
        });
        at = hi;
    }
    if at < x1 {
        pieces.push(Node {
            bbox: [at, y0, x1, y1],
            ..placeholder()
        });
    }
    band.children = pieces;
    band.split = Some(Axis::X);
}
