//! Bracket sets counted by their pitch: a labelled tree and its ink -> the
//! bracket layer re-cut where its sets repeat, when the sets read from its
//! regions are not as many as the ink repeats.
//!
//! The regions are the better reading where they hold (each set's own
//! box), and they hold on clean drawings (199 of the round trip's 200).
//! A shaky scan breaks the layer's back into pieces, or joins it to the
//! rafters, and the pieces are then counted instead of the sets (13 read
//! for 38, 60 for 31); a blur closes the back between sets. The ink still
//! repeats. Not at the sets' edges: a set 0.6 of its 1.1 m pitch has its
//! edges nearly evenly spaced, and their autocorrelation peaks at half or
//! double the pitch (the front's count right in 23 to 143 of 200 clean
//! drawings, by the threshold). Along the sets' lower edges it is a square
//! wave, ink under each set and none under the back, whose autocorrelation
//! is low at half the pitch. Each strip of 3 rows of the layer (a column
//! is inked when any of its 3 pixels is: a jittered line moves a row) with
//! 20 to 80 % of the front inked is a candidate; the one that repeats
//! best gives the pitch. The front's count is right so in 200 of 200
//! drawings clean, with gaps, with jitter and with a blur.

use super::super::drawing::Ink;
use super::super::tree::Node;
use super::{folded, front, labelled, lay_out, rhythm, Rhythm, MIN_COUNT};

/// Rows of a strip: a line shaken by a row stays in it.
const STRIP: i32 = 3;
/// The share of the front a strip along the sets' lower edges inks: as
/// much as the sets are wide, about half.
const INKED: std::ops::RangeInclusive<f64> = 0.2..=0.8;

/// Re-cuts the bracket layer of `root` at the pitch its ink repeats at,
/// when the sets read from its regions are more than two off the front's
/// count by that pitch and the corner sets drawn, or have lost corner
/// sets drawn at both ends. Returns the rhythm when it re-cut.
pub fn brackets(root: &mut Node, ink: &Ink) -> Option<Rhythm> {
    let (x0, x1) = front(root, ink)?;
    let band_at = root
        .children
        .iter()
        .position(|b| labelled(b, "bracket") > 0)?;
    let sets = labelled(&root.children[band_at], "bracket");
    let band = &mut root.children[band_at];
    let [bx0, y0, bx1, y1] = band.bbox;
    let (ux0, ux1) = (
        (bx0 - 2).max(0) as usize,
        ((bx1 + 2).max(0) as usize).min(ink.width),
    );
    if x0 < bx0 || x1 > bx1 || x1 as usize > ux1 {
        return None;
    }
    let strip = |y: i32| -> Vec<f64> {
        let rows = y.max(0) as usize..((y + STRIP).max(0) as usize).min(ink.height);
        (ux0..ux1)
            .map(|x| f64::from(u8::from(rows.clone().any(|y| ink.at(x, y)))))
            .collect()
    };
    let on_front = |f: &[f64]| f[x0 as usize - ux0..x1 as usize - ux0].to_vec();
    let (rhythm, f) = (y0 + 1..y1 - STRIP)
        .filter_map(|y| {
            let f = strip(y);
            let front = on_front(&f);
            let inked = front.iter().sum::<f64>() / front.len() as f64;
            if !INKED.contains(&inked) {
                return None;
            }
            Some((rhythm(&front)?, f))
        })
        .max_by(|a, b| a.0.periodicity.total_cmp(&b.0.periodicity))?;
    let n = ((x1 - x0) as f64 / rhythm.pitch).round() as i64;
    if n < MIN_COUNT as i64 {
        return None;
    }
    let pitch = (x1 - x0) as f64 / n as f64;
    let (phase, width) = square(&on_front(&f), pitch);
    let half = (width / 2.0).max(0.5);
    let boxes: Vec<(i32, i32)> = (0..n)
        .map(|i| {
            let c = x0 as f64 + phase + i as f64 * pitch;
            ((c - half).floor() as i32, (c + half).ceil() as i32)
        })
        .collect();
    // A side face's first set seen end-on at each corner, beyond the
    // middle of the back before the front's first set (after its last).
    let back = ((pitch - width) / 2.0).max(1.0) as i32;
    let (start, end) = (boxes[0].0 - back, boxes[boxes.len() - 1].1 + back);
    // A block's lower edge drawn there: a run of 3 inked columns (a line
    // crossing the strip inks one or two).
    let drawn = |lo: i32, hi: i32| {
        let xs = lo.max(ux0 as i32)..hi.min(ux1 as i32);
        let mut run = 0;
        let longest = xs.fold(0, |m, x| {
            run = if f[x as usize - ux0] > 0.0 {
                run + 1
            } else {
                0
            };
            m.max(run)
        });
        longest >= 3
    };
    let corners =
        (start > bx0 && end < bx1 && drawn(bx0, start) && drawn(end, bx1)).then_some((start, end));
    // The regions' reading stands unless it is more than two sets off the
    // front's count and the corners', or has lost a corner set or both
    // where both are drawn. Hand-drawn rows are laid out otherwise than
    // the front's count assumes (sets past the end columns, a set short
    // of the ends) and are read right by their regions: one or two sets
    // off the ink's count is left to them.
    let expected = n + 2 * i64::from(corners.is_some());
    let sets = sets as i64;
    let lost_corners = corners.is_some() && (n..expected).contains(&sets);
    if (sets - expected).abs() <= 2 && !lost_corners {
        return None;
    }
    lay_out(band, "bracket", &boxes, corners);
    Some(rhythm)
}

/// The square wave `f` folded at `pitch`: the centre of the longest run
/// of the period inked in at least half its columns (from the front's
/// start), and the run's width.
fn square(f: &[f64], pitch: f64) -> (f64, f64) {
    let bins = (pitch.round() as usize).max(2);
    let inked: Vec<bool> = folded(f, pitch, bins).iter().map(|&h| h >= 0.5).collect();
    // The longest circular run of inked bins: start and length.
    let (mut best, mut run) = ((0, 0), None);
    for k in 0..2 * bins {
        match (inked[k % bins], run) {
            (true, None) => run = Some(k),
            (false, Some(a)) => {
                if k - a > best.1 {
                    best = (a, (k - a).min(bins));
                }
                run = None;
            }
            _ => {}
        }
    }
    if let Some(a) = run {
        if 2 * bins - a > best.1 {
            best = (a, (2 * bins - a).min(bins));
        }
    }
    let bin = pitch / bins as f64;
    let centre = (best.0 as f64 + best.1 as f64 / 2.0) * bin;
    (centre.rem_euclid(pitch), best.1 as f64 * bin)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::infer::tree::Axis;

    #[test]
    fn a_square_wave_folds_to_its_inked_run() {
        // Ink over 6 of every 11 pixels, from pixel 3 of each period.
        let f: Vec<f64> = (0..440)
            .map(|x| f64::from(u8::from((3..9).contains(&(x % 11)))))
            .collect();
        let (centre, width) = square(&f, 11.0);
        assert!((centre - 6.0).abs() <= 0.5, "{centre}");
        assert!((width - 6.0).abs() <= 1.0, "{width}");
    }

    /// A hall's bracket layer (rows 40..60 of a 1000 x 100 page) drawn as
    /// `hall.lsys` draws it: blocks 0.6 of an 11.5-pixel pitch hanging 14
    /// rows from the top line, between the end columns' centres at 100
    /// and 905; `read` bracket leaves stand in for the regions' reading.
    fn hall(read: usize, corners: bool) -> (Node, Ink) {
        let (width, height) = (1000, 100);
        let mut ink = vec![false; width * height];
        let pitch = 805.0 / 70.0;
        for i in 0..70 {
            let c = 100.0 + (i as f64 + 0.5) * pitch;
            let (lo, hi) = ((c - 3.45) as usize, (c + 3.45) as usize);
            for y in 40..54 {
                ink[y * width + lo] = true;
                ink[y * width + hi] = true;
            }
            for x in lo..=hi {
                ink[54 * width + x] = true;
            }
        }
        for x in 60..940 {
            ink[40 * width + x] = true;
        }
        // Each corner's set seen end-on: a block from the band's end.
        if corners {
            for (lo, hi) in [(62, 80), (925, 938)] {
                for x in lo..=hi {
                    ink[54 * width + x] = true;
                }
            }
        }
        let sets = (0..read)
            .map(|i| {
                Node::leaf(
                    "bracket",
                    [100 + 10 * i as i32, 40, 105 + 10 * i as i32, 60],
                )
            })
            .collect();
        let mut band = Node::leaf("other", [60, 40, 940, 60]);
        band.children = sets;
        band.split = Some(Axis::X);
        let mut body = Node::leaf("other", [60, 60, 940, 100]);
        body.children = vec![
            Node::leaf("column", [96, 60, 104, 100]),
            Node::leaf("column", [901, 60, 909, 100]),
        ];
        let mut root = Node::leaf("other", [60, 40, 940, 100]);
        root.children = vec![band, body];
        root.split = Some(Axis::Y);
        (root, Ink { width, height, ink })
    }

    fn sets(root: &Node) -> usize {
        labelled(root, "bracket")
    }

    #[test]
    fn sets_miscounted_by_their_regions_are_counted_by_their_pitch() {
        for (read, corners, want) in [(13, false, 70), (13, true, 72), (70, true, 72)] {
            let (mut root, ink) = hall(read, corners);
            let r = brackets(&mut root, &ink).expect("re-cut");
            assert!((r.pitch - 805.0 / 70.0).abs() < 0.05, "{r:?}");
            assert_eq!(sets(&root), want, "{read} read, corners {corners}");
        }
    }

    #[test]
    fn sets_the_regions_count_as_the_ink_repeats_are_left_as_read() {
        for (read, corners) in [(70, false), (71, false), (72, true), (73, true)] {
            let (mut root, ink) = hall(read, corners);
            assert_eq!(brackets(&mut root, &ink), None);
            assert_eq!(sets(&root), read);
        }
    }
}
