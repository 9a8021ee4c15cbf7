//! The rafter row read by its pitch: a labelled shape tree and its ink ->
//! the same tree with the rafter row cut where its ink repeats.
//!
//! Rafter ends are the smallest thing an elevation draws: at 1000 pixels
//! across a 38-metre hall a rafter is 3.5 pixels wide and the back between
//! two 5. Thickening the lines to bridge gaps (`--gap`) closes both, and
//! the regions that are left are a handful of pieces, or posts of ink
//! closed in some places and open in others once a scan jitters (the
//! round trip counted 2 rafters for 98, and 76 for 48). The seed's answer
//! to rows like this is repeated-pattern detection; here it is done on the
//! ink itself, which keeps every line: the row's profile (ink per column,
//! over the layer's inner rows, between the end columns' centres, where
//! the front's rafters run) repeats at the rafters' pitch. Its
//! autocorrelation's first strong peak is the pitch, refined on peaks at
//! doubling multiples of it to a hundredth of a pixel; the front holds
//! its width over the pitch, rounded; the profile folded at the pitch puts
//! the two edges of a rafter, the nearer pair of lines (a rafter is
//! narrower than the back between two).
use super::super::drawing::Ink;
use super::super::tree::Node;
use super::{front, labelled, lay_out, profile, rhythm, Rhythm, MIN_COUNT};

/// Re-cuts the rafter layer of `root` at its ink's pitch, when the front
/// between the end columns' centres repeats at least [`MIN_COUNT`] times.
/// Returns the row's rhythm, if it was read so.
pub fn rafters(root: &mut Node, ink: &Ink) -> Option<Rhythm> {
    let (x0, x1) = front(root, ink)?;
    let band_at = rafter_band(root).or_else(|| cut_joined_row(root, ink, x0, x1))?;
    let band = &mut root.children[band_at];
    let [bx0, y0, bx1, y1] = band.bbox;
    if y1 - y0 < 3 {
        return None;
    }
    let rows = inner_rows(y0, y1, ink);
    // Two pixels past the band's ends: its boxes end in the middle of its
    // outermost lines.
    let (ux0, ux1) = (
        (bx0 - 2).max(0) as usize,
        ((bx1 + 2).max(0) as usize).min(ink.width),
    );
    if rows.is_empty() || x0 < bx0 || x1 > bx1 || x1 as usize > ux1 {
        return None;
    }
    // The whole layer's profile, from the band's left end; the front's
    // part of it gives the rhythm.
    let full = profile(ink, ux0, ux1, rows);
    let ink_at = |x: f64| -> f64 {
        let i = x.round() as i64 - ux0 as i64;
        (i - 1..=i + 1)
            .filter_map(|j| usize::try_from(j).ok().and_then(|j| full.get(j)))
            .copied()
            .fold(0.0, f64::max)
    };
    let rhythm = rhythm(full.get(x0 as usize - ux0..x1 as usize - ux0)?)?;
    let n = ((x1 - x0) as f64 / rhythm.pitch).round() as i64;
    if n < MIN_COUNT as i64 {
        return None;
    }
    let pitch = (x1 - x0) as f64 / n as f64;
    let half = (rhythm.width / 2.0).max(0.5);
    let centre = |i: i64| x0 as f64 + rhythm.phase.min(pitch) + i as f64 * pitch;
    // Both edges of element i drawn, and the back on either side: the
    // front's elements say how much ink each has.
    let edges = |i: i64| ink_at(centre(i) - half).min(ink_at(centre(i) + half));
    let back = |i: i64| ink_at(centre(i) - pitch / 2.0).max(ink_at(centre(i) + pitch / 2.0));
    let middle = |v: Vec<f64>| {
        let mut v = v;
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (edge_ink, back_ink) = (
        middle((0..n).map(edges).collect()),
        middle((0..n).map(back).collect()),
    );
    // Elements go on past the front's ends as long as they are drawn
    // alike (a hand-drawn row under the eaves' overhang); the layer's
    // pieces beyond are then a side face's element seen end-on when they
    // hold a line (the corner's rafter under the eaves).
    let alike = |i: i64| {
        let (lo, hi) = (centre(i) - pitch / 2.0, centre(i) + pitch / 2.0);
        lo >= bx0 as f64
            && hi <= bx1 as f64
            && edges(i) >= 0.5 * edge_ink
            && back(i) <= back_ink + 0.5 * (edge_ink - back_ink)
    };
    let (mut first, mut last) = (0, n - 1);
    while alike(first - 1) {
        first -= 1;
    }
    while alike(last + 1) {
        last += 1;
    }
    let box_of = |i: i64| {
        let c = centre(i);
        ((c - half).floor() as i32, (c + half).ceil() as i32)
    };
    let drawn = |lo: i32, hi: i32| (lo..=hi).any(|x| ink_at(x as f64) > 0.0);
    let (start, end) = (
        box_of(first).0 - (pitch / 2.0) as i32,
        box_of(last).1 + (pitch / 2.0) as i32,
    );
    let corners = start - bx0 > pitch as i32
        && bx1 - end > pitch as i32
        && drawn(bx0, start)
        && drawn(end, bx1);
    let boxes: Vec<(i32, i32)> = (first..=last).map(box_of).collect();
    lay_out(band, "rafter", &boxes, corners.then_some((start, end)));
    Some(rhythm)
}

/// The layer's inner rows: its boxes reach the middle of its top and
/// bottom lines, which run the row's length and would only add a
/// constant.
fn inner_rows(y0: i32, y1: i32, ink: &Ink) -> std::ops::Range<usize> {
    let inset = if y1 - y0 >= 7 { 2 } else { 1 };
    (y0 + inset).max(0) as usize..((y1 - inset).max(0) as usize).min(ink.height)
}

/// A row of ink is a line across the front when it covers this much of it.
const ACROSS: f64 = 0.8;

/// A rafter layer the shape tree did not cut off (a layer 5 pixels high, or
/// blurred): the strip at the top of the bracket layer, down to the first
/// line drawn across it, or at the bottom of the roof, up to the first
/// line across above the eaves' line. Taken when its ink repeats at
/// least [`MIN_COUNT`] times, and half as often again as the bracket
/// sets: it is cut from its band as a band of its own. Returns its index.
fn cut_joined_row(root: &mut Node, ink: &Ink, x0: i32, x1: i32) -> Option<usize> {
    let bands = &root.children;
    let roof = bands.iter().position(|b| b.label == "roof")?;
    let brackets = roof + 1;
    let sets = labelled(bands.get(brackets)?, "bracket");
    if sets == 0 {
        return None;
    }
    // Over two rows: a line drawn between two rows of pixels is split
    // between them where it was smoothed.
    let drawn = |y: i32, rows: i32| {
        let ys = y.max(0) as usize..((y + rows).max(0) as usize).min(ink.height);
        let n = (x0..x1)
            .filter(|&x| ys.clone().any(|y| ink.at(x as usize, y)))
            .count();
        n as f64 / (x1 - x0) as f64
    };
    let across = |y: i32| drawn(y, 2) >= ACROSS;
    // From `from` towards `to` (excluded): past the line at `from`, rows
    // not drawn across, then the middle of the next line.
    let next_line = |from: i32, to: i32| -> Option<i32> {
        let step = (to - from).signum();
        let inside = |y: i32| y != to && y >= 0 && (y as usize) < ink.height;
        // The band's edge is the middle of its line, or a row or two off
        // it where the line is thick or blurred; or there is no line there.
        let mut y = (0..3)
            .map(|k| from + k * step)
            .find(|&y| inside(y) && across(y))
            .unwrap_or(from);
        while inside(y) && across(y) {
            y += step;
        }
        let open = y;
        while inside(y) && !across(y) {
            y += step;
        }
        if !inside(y) || (y - open).abs() < 2 {
            return None;
        }
        let start = y;
        while inside(y + step) && across(y + step) {
            y += step;
        }
        // The line's own rows: those of the pairs drawn half across alone.
        let (lo, hi) = (start.min(y), start.max(y) + 1);
        let own: Vec<i32> = (lo..=hi).filter(|&y| drawn(y, 1) >= ACROSS / 2.0).collect();
        let (first, last) = (own.first().copied()?, own.last().copied()?);
        Some((first + last) / 2)
    };
    let (r, b) = (bands[roof].bbox, bands[brackets].bbox);
    // At the top of the bracket layer (index `brackets`), or at the
    // bottom of the roof.
    let candidates = [
        next_line(b[1], b[1] + (b[3] - b[1]) / 2).map(|cut| (b[1], cut, true)),
        next_line(r[3], r[3] - (r[3] - r[1]) / 3).map(|cut| (cut, r[3], false)),
    ];
    for (ya, yb, in_brackets) in candidates.into_iter().flatten() {
        if yb - ya < 3 {
            continue;
        }
        let f = profile(ink, x0 as usize, x1 as usize, inner_rows(ya, yb, ink));
        let Some(rhythm) = rhythm(&f) else {
            continue;
        };
        let n = (x1 - x0) as f64 / rhythm.pitch;
        if n < MIN_COUNT as f64 || n < 1.5 * sets as f64 {
            continue;
        }
        let [bx0, _, bx1, _] = b;
        let band = Node::leaf("other", [bx0, ya, bx1, yb]);
        if in_brackets {
            clip_top(&mut root.children[brackets], yb);
            root.children.insert(brackets, band);
            return Some(brackets);
        }
        root.children[roof].bbox[3] = ya;
        root.children.insert(roof + 1, band);
        return Some(roof + 1);
    }
    None
}

/// `n` and everything in it start at `y` at the earliest.
fn clip_top(n: &mut Node, y: i32) {
    n.bbox[1] = n.bbox[1].max(y).min(n.bbox[3]);
    for c in &mut n.children {
        clip_top(c, y);
    }
}

/// The top-level band holding the rafters: the one with rafter leaves, or
/// else the one between the roof and the bracket layer.
fn rafter_band(root: &Node) -> Option<usize> {
    let holds = |n: &Node, label: &str| labelled(n, label) > 0;
    let bands = &root.children;
    if let Some(i) = bands.iter().position(|b| holds(b, "rafter")) {
        return Some(i);
    }
    let roof = bands.iter().position(|b| b.label == "roof")?;
    let brackets = bands.iter().position(|b| holds(b, "bracket"))?;
    (brackets == roof + 2).then_some(roof + 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::infer::tree::Axis;

    /// A row of `n` elements `w` wide at `pitch` from `x0`, drawn as one
    /// pixel line at each edge, rows `y0..y1` of a 1000 x 100 page; the
    /// row's top and bottom lines drawn across it.
    fn row(x0: f64, pitch: f64, w: f64, n: usize, (y0, y1): (usize, usize)) -> Ink {
        row_and(x0, pitch, w, n, (y0, y1), &[])
    }

    /// [`row`] and a line at each of `more`.
    fn row_and(
        x0: f64,
        pitch: f64,
        w: f64,
        n: usize,
        (y0, y1): (usize, usize),
        more: &[f64],
    ) -> Ink {
        let (width, height) = (1000, 100);
        let mut ink = vec![false; width * height];
        let mut line = |x: f64| {
            for y in y0..y1 {
                ink[y * width + x.floor() as usize] = true;
            }
        };
        for i in 0..n {
            let c = x0 + (i as f64 + 0.5) * pitch;
            line(c - w / 2.0);
            line(c + w / 2.0);
        }
        for &x in more {
            line(x);
        }
        for x in 0..width {
            ink[y0 * width + x] = true;
            ink[(y1 - 1) * width + x] = true;
        }
        Ink { width, height, ink }
    }

    fn band(label: &'static str, bbox: [i32; 4], children: Vec<Node>) -> Node {
        let mut n = Node::leaf(label, bbox);
        n.split = (!children.is_empty()).then_some(Axis::X);
        n.children = children;
        n
    }

    #[test]
    fn a_pitch_between_whole_pixels_is_read_to_a_hundredth() {
        // 9.37 px: lines fall 9 and 10 pixels apart by turns.
        let ink = row(100.0, 9.37, 3.7, 85, (10, 18));
        let f = profile(&ink, 100, 100 + (85.0 * 9.37) as usize, 12..16);
        let r = rhythm(&f).expect("a rhythm");
        assert!((r.pitch - 9.37).abs() < 0.02, "{r:?}");
        assert!((r.width - 3.7).abs() < 0.8, "{r:?}");
        // The first element's centre half a pitch in.
        assert!((r.phase - 9.37 / 2.0).abs() < 1.0, "{r:?}");
    }

    #[test]
    fn ink_that_does_not_repeat_has_no_rhythm() {
        let mut f = vec![0.0; 600];
        for (k, x) in [3usize, 40, 41, 170, 333, 334, 335, 512].iter().enumerate() {
            f[*x] = 1.0 + k as f64;
        }
        assert_eq!(rhythm(&f), None);
        assert_eq!(rhythm(&[2.0; 600]), None);
    }

    /// The hall's tree as the recogniser leaves it: a roof, an empty
    /// rafter band at rows 40..47, a bracket band and a body whose end
    /// columns stand at 100 and 901.
    fn hall() -> Node {
        let mut root = band(
            "other",
            [60, 0, 940, 100],
            vec![
                Node::leaf("roof", [60, 0, 940, 40]),
                band("other", [60, 40, 940, 47], Vec::new()),
                band(
                    "other",
                    [60, 47, 940, 60],
                    vec![Node::leaf("bracket", [90, 47, 110, 60])],
                ),
                band(
                    "other",
                    [60, 60, 940, 100],
                    vec![
                        Node::leaf("column", [96, 60, 104, 100]),
                        Node::leaf("bay", [104, 60, 897, 100]),
                        Node::leaf("column", [897, 60, 905, 100]),
                    ],
                ),
            ],
        );
        root.split = Some(Axis::Y);
        root
    }

    fn rafter_boxes(root: &Node) -> Vec<[i32; 4]> {
        root.children[1]
            .children
            .iter()
            .filter(|c| c.label == "rafter")
            .map(|c| c.bbox)
            .collect()
    }

    #[test]
    fn a_rafter_row_closed_into_ink_is_counted_by_its_pitch() {
        // 90 rafters at 8.9 px between the end columns' centres, a side
        // rafter seen end-on beyond each end (a box from the band's end);
        // the band has no regions left (gap bridging closed them), so it
        // is found between the roof and the bracket layer.
        let ink = row_and(100.0, 8.9, 3.5, 90, (40, 48), &[61.0, 938.0]);
        let mut root = hall();
        let r = rafters(&mut root, &ink).expect("read by its pitch");
        assert!((r.pitch - 8.9).abs() < 0.05, "{r:?}");
        let rafters = rafter_boxes(&root);
        assert_eq!(rafters.len(), 92, "90 on the front, 2 at the corners");
        // Each front rafter's box holds its centre.
        for (i, b) in rafters[1..91].iter().enumerate() {
            let c = 100.0 + (i as f64 + 0.5) * 8.9;
            assert!((b[0] as f64) <= c && c <= b[2] as f64, "rafter {i}: {b:?}");
        }
        assert!(root.children[1].repeat);
    }

    #[test]
    fn rafters_drawn_on_under_the_eaves_are_each_one() {
        // A hand-drawn row: the same rafters go on four pitches past each
        // end column, and nothing is drawn beyond them (no corner).
        let ink = row(100.0 - 4.0 * 8.9, 8.9, 3.5, 98, (40, 48));
        let mut root = hall();
        rafters(&mut root, &ink).expect("read by its pitch");
        assert_eq!(rafter_boxes(&root).len(), 98);
    }

    #[test]
    fn a_rafter_row_the_tree_left_in_the_bracket_layer_is_cut_off() {
        // The rafters, 5 rows high, over a line across the front at row
        // 45, all in the bracket layer's band (rows 40..60): no cut was
        // found between them and the sets.
        let mut ink = row_and(100.0, 8.9, 3.5, 90, (40, 46), &[61.0, 938.0]);
        for x in 60..940 {
            ink.ink[59 * ink.width + x] = true;
        }
        let mut root = hall();
        let sets = root.children.remove(2);
        root.children[1] = sets;
        root.children[1].bbox[1] = 40;
        rafters(&mut root, &ink).expect("cut off and read by its pitch");
        let bands: Vec<[i32; 4]> = root.children.iter().map(|b| b.bbox).collect();
        assert_eq!(bands[1], [60, 40, 940, 45], "{bands:?}");
        assert_eq!(bands[2][1], 45, "the bracket layer starts under the line");
        assert_eq!(rafter_boxes(&root).len(), 92);
    }
}
