//! The drawing round trip, measured (issue 33, item 5).
//!
//! Input: `examples/shapes/hall.lsys`, sampled over its parameters with a
//! seeded generator. Each sample is drawn as `lsys render hall.lsys --view
//! front --style lines --size 1000x600 -D ...` draws it, read back by
//! `lsys infer`'s driver entry, also after three kinds of damage, and
//! compared with what the generator built: the counts, each label's pixels
//! (IoU), the shape tree (Zhang–Shasha edit distance), and the inferred
//! grammar rebuilt at other widths.
//!
//! Output: `docs/drawing-roundtrip.md` (or `--out FILE`), numbers only.
//!
//! ```text
//! cargo run --release --example drawing_roundtrip             # 200 drawings
//! cargo run --release --example drawing_roundtrip -- --quick  # 20, to stdout
//!     [--count N] [--seed S] [--out FILE] [--overlay DIR [--drawing K]]
//! ```
//!
//! `--overlay DIR` writes drawing K (0 unless told) as it was read in each
//! condition, and beside it the truth boxes painted over it with the
//! inferred leaves outlined, to check the truth's projection by eye.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::Vec3;
use lsys::driver::{InferOptions, Inference};
use lsys::internals::export::render::{render, Image, PixelFrame, RenderOptions, Style, View};
use lsys::internals::infer::Node;
use lsys::internals::lang::scope_commands::Axis;
use lsys::internals::turtle::scope::{repeat, symmetric, Role};
use lsys::Grammar;

#[path = "common/roundtrip.rs"]
mod roundtrip;
use roundtrip::{damaged, ink_box, measure_all, png_bytes, read, Mask, SplitMix, CONDITIONS};

const HALL: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/shapes/hall.lsys");
/// Where the hall's sizes (`#define`s) are: the parts it includes.
const HALL_SIZES: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/examples/shapes/hall_parts.lsys"
);
const DOC: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/drawing-roundtrip.md");
/// The drawing size `tests/infer.rs` and `docs/drawing.md` use.
const SIZE: (u32, u32) = (1000, 600);
const SEED: u64 = 33;
const FULL: usize = 200;
const QUICK: usize = 20;
/// Drawings the width test rebuilds (the first that qualify).
const WIDTH_DRAWINGS: usize = 40;
const FACTORS: [f64; 4] = [0.7, 0.85, 1.25, 1.5];

/// The sampled parameters: name, low, high. Each is uniform in its range,
/// rounded to 0.01. Every combination is a hall: the ends and the centre
/// fit in the narrowest width (2 * 2.4 + 5.0 < 14), a room of 3.2 still
/// has a window between its sill (1.0), head (0.4) and lintel (0.6), and
/// a visible ridge needs RIDGE above its 0.25 sunk into the roof.
const PARAMS: [(&str, f64, f64); 10] = [
    ("W", 14.0, 40.0),
    ("BAY", 2.2, 4.0),
    ("END", 1.2, 2.4),
    ("CENTRE", 3.2, 5.0),
    ("ROOM", 3.2, 5.2),
    ("ROOF", 1.8, 3.6),
    ("BRK", 0.5, 1.2),
    ("RAF", 0.25, 0.5),
    ("PLAT", 0.5, 1.5),
    ("RIDGE", 0.4, 0.9),
];

// Sizes written as literals in hall.lsys's rules (not `#define`s), which
// the truth boxes need. The `#define`s it does not sample (COL, LINTEL,
// OV) are read from the file instead.
/// `BrkFace --> @RX(1.1)`.
const BRK_PITCH: f64 = 1.1;
/// `BrkSet --> @SX(flo(1), 0.6, flo(1))`, its top `rel(0.7)` drawn.
const BRK_SET: (f64, f64) = (0.6, 0.7);
/// `@Ext(0.35)`: how far a set stands out of its face.
const BRK_OUT: f64 = 0.35;
/// `RafFace --> @RX(0.4)`.
const RAF_PITCH: f64 = 0.4;
/// `Below --> @SY(1.0, flo(1), 0.4)` and `@SX(0.4, flo(1), 0.4)`.
const WINDOW_SILL: f64 = 1.0;
const WINDOW_HEAD: f64 = 0.4;
const WINDOW_SIDE: f64 = 0.4;
/// `Door --> @SX(flo(1), rel(0.7), flo(1))`.
const DOOR_FRAC: f64 = 0.7;
/// `Platform --> @Tr(-0.6, ..) @Grow(1.2, ..)`.
const PLAT_OV: f64 = 0.6;

/// One sampled hall: the values of [`PARAMS`], in order.
#[derive(Clone, Copy, Debug)]
struct Hall([f64; 10]);

impl Hall {
    fn sample(rng: &mut SplitMix) -> Hall {
        Hall(PARAMS.map(|(_, lo, hi)| ((lo + (hi - lo) * rng.unit()) * 100.0).round() / 100.0))
    }
    fn get(&self, name: &str) -> f64 {
        let k = PARAMS
            .iter()
            .position(|p| p.0 == name)
            .expect("a parameter");
        self.0[k]
    }
    fn with_width(&self, w: f64) -> Hall {
        self.with("W", w)
    }
    /// The same hall with parameter `name` set to `v`.
    fn with(&self, name: &str, v: f64) -> Hall {
        let k = PARAMS
            .iter()
            .position(|p| p.0 == name)
            .expect("a parameter");
        let mut h = *self;
        h.0[k] = v;
        h
    }
    /// `W=24.37 BAY=3.1 ...`: also the `-D`s that redraw it.
    fn shown(&self) -> String {
        PARAMS
            .iter()
            .zip(self.0)
            .map(|((n, _, _), v)| format!("{n}={v}"))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// hall.lsys's other `#define`s the truth needs.
#[derive(Clone, Copy, Debug)]
struct Fixed {
    col: f64,
    lintel: f64,
    ov: f64,
}

fn read_fixed(text: &str) -> Fixed {
    let defines: BTreeMap<&str, f64> = text
        .lines()
        .filter_map(|l| {
            let mut w = l.strip_prefix("#define ")?.split_whitespace();
            Some((w.next()?, w.next()?.parse().ok()?))
        })
        .collect();
    let get = |n: &str| {
        *defines
            .get(n)
            .unwrap_or_else(|| panic!("hall_parts.lsys defines {n}"))
    };
    Fixed {
        col: get("COL"),
        lintel: get("LINTEL"),
        ov: get("OV"),
    }
}

/// What a hall has, by the generator's own splits or as read back.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
struct Counts {
    bays: usize,
    columns: usize,
    doors: usize,
    windows: usize,
    brackets: usize,
    rafters: usize,
}

impl Counts {
    /// Bays, columns, doors, windows and bracket sets.
    fn five(&self) -> [usize; 5] {
        [
            self.bays,
            self.columns,
            self.doors,
            self.windows,
            self.brackets,
        ]
    }
    /// The five, and the rafters.
    fn six(&self) -> [usize; 6] {
        let [b, c, d, w, s] = self.five();
        [b, c, d, w, s, self.rafters]
    }
}

const COUNT_NAMES: [&str; 5] = ["bays", "columns", "doors", "windows", "bracket sets"];

/// The generator's layout: `@RSX(END, BAY, CENTRE)` pieces, bracket sets
/// and rafters by `@RX`.
struct Truth {
    pieces: Vec<(Role, f64)>,
    brackets: usize,
    rafters: usize,
}

fn truth(h: &Hall) -> Result<Truth, String> {
    truth_pitched(h, BRK_PITCH)
}

/// [`truth`] with bracket sets `@RX(pitch)` for `@RX(1.1)`.
fn truth_pitched(h: &Hall, pitch: f64) -> Result<Truth, String> {
    let w = h.get("W");
    let pieces = symmetric(w, h.get("END"), h.get("BAY"), h.get("CENTRE"), Axis::X)
        .map_err(|e| e.problem)?;
    // Bracket sets and rafters go round all four faces: the front view
    // also shows, at each end, a side face's first one end-on.
    let brackets = repeat(w, pitch, Axis::X).map_err(|e| e.problem)?.len() + 2;
    let rafters = repeat(w, RAF_PITCH, Axis::X).map_err(|e| e.problem)?.len() + 2;
    Ok(Truth {
        pieces,
        brackets,
        rafters,
    })
}

impl Truth {
    fn counts(&self) -> Counts {
        let role = |r: Role| self.pieces.iter().filter(|p| p.0 == r).count();
        Counts {
            bays: self.pieces.len(),
            columns: self.pieces.len() + 1,
            doors: role(Role::Centre),
            windows: role(Role::Bay),
            brackets: self.brackets,
            rafters: self.rafters,
        }
    }
}

/// Labels whose pixels are compared.
const IOU_LABELS: [&str; 7] = [
    "column", "door", "window", "bracket", "roof", "platform", "stairs",
];

/// The truth's boxes in model coordinates (metres, y up), `[x0, y0, x1,
/// y1]`, by label, from hall.lsys's splits.
fn truth_boxes(h: &Hall, t: &Truth, f: &Fixed) -> Vec<(&'static str, [f64; 4])> {
    let w = h.get("W");
    let (plat, room, brk, raf) = (h.get("PLAT"), h.get("ROOM"), h.get("BRK"), h.get("RAF"));
    let mut out = Vec::new();
    // Bay boundaries; a column (`Pier`, and the last one of `Corridor`)
    // COL wide centred on each.
    let mut edges = vec![0.0];
    for p in &t.pieces {
        edges.push(edges[edges.len() - 1] + p.1);
    }
    for &b in &edges {
        out.push((
            "column",
            [b - f.col / 2.0, plat, b + f.col / 2.0, plat + room],
        ));
    }
    let below = plat + room - f.lintel;
    for (k, p) in t.pieces.iter().enumerate() {
        let (a, b) = (edges[k], edges[k + 1]);
        match p.0 {
            Role::Bay => out.push((
                "window",
                [
                    a + WINDOW_SIDE,
                    plat + WINDOW_SILL,
                    b - WINDOW_SIDE,
                    below - WINDOW_HEAD,
                ],
            )),
            Role::Centre => {
                let side = (b - a) * (1.0 - DOOR_FRAC) / 2.0;
                out.push(("door", [a + side, plat, b - side, below]));
            }
            Role::End => {}
        }
    }
    // Bracket sets: the middle BRK_SET.0 of each repeat piece, the top
    // BRK_SET.1 of the layer.
    let front = t.brackets - 2;
    let pitch = w / front as f64;
    let top = plat + room + brk;
    for k in 0..front {
        let c = (k as f64 + 0.5) * pitch;
        out.push((
            "bracket",
            [
                c - BRK_SET.0 / 2.0,
                top - BRK_SET.1 * brk,
                c + BRK_SET.0 / 2.0,
                top,
            ],
        ));
    }
    // The side faces' first sets, end-on: as deep as a set stands out.
    for (x0, x1) in [(-BRK_OUT, 0.0), (w, w + BRK_OUT)] {
        out.push(("bracket", [x0, top - BRK_SET.1 * brk, x1, top]));
    }
    // The roof's front slope, OV beyond the facade on each side.
    let base = top + raf;
    out.push(("roof", [-f.ov, base, w + f.ov, base + h.get("ROOF")]));
    // The platform, the stairs CENTRE wide in its middle.
    let (s0, s1) = ((w - h.get("CENTRE")) / 2.0, (w + h.get("CENTRE")) / 2.0);
    out.push(("platform", [-PLAT_OV, 0.0, s0, plat]));
    out.push(("platform", [s1, 0.0, w + PLAT_OV, plat]));
    out.push(("stairs", [s0, 0.0, s1, plat]));
    out
}

/// Model -> drawing pixels through the renderer's own framing
/// ([`PixelFrame`]); [`draw`] checks it against the ink of every drawing.
#[derive(Clone, Copy, Debug)]
struct Frame(PixelFrame);

impl Frame {
    /// A model box `[x0, y0, x1, y1]` (y up, front view) as a pixel box,
    /// y down.
    fn project(&self, b: [f64; 4]) -> [f64; 4] {
        let at = |x: f64, y: f64| self.0.project(Vec3::new(x as f32, y as f32, 0.0));
        let (top_left, bottom_right) = (at(b[0], b[3]), at(b[2], b[1]));
        [
            top_left.x as f64,
            top_left.y as f64,
            bottom_right.x as f64,
            bottom_right.y as f64,
        ]
    }
}

/// `lsys infer`'s reading of a picture; a hall taken for a Pailou's front
/// (read by synthesis) counts as unread.
fn read_hall(bytes: &[u8], name: &str) -> Result<Inference, String> {
    let inference = read(bytes, name)?;
    match &inference.summary {
        Some(s) => Err(format!("read as {s}")),
        None => Ok(inference),
    }
}

fn render_options() -> RenderOptions {
    // What `lsys render --view front --style lines --size 1000x600` asks.
    RenderOptions {
        view: View::Front,
        style: Style::Lines,
        width: SIZE.0,
        height: SIZE.1,
        ..RenderOptions::default()
    }
}

/// Draws `hall` as the command line does; the picture and its framing.
fn draw(hall: &Hall) -> Result<(Image, Frame), String> {
    let mut o = Grammar::options();
    for ((name, _, _), v) in PARAMS.iter().zip(hall.0) {
        o = o.define(name, v);
    }
    let g = o.from_path(HALL).map_err(|e| e.to_string())?;
    // `lsys render` without `-n` derives the file's derivation length.
    let scene = g.build(g.derivation_length()).map_err(|e| e.to_string())?;
    let opts = render_options();
    let image = render(scene.mesh(), &opts);
    let (lo, hi) = scene.bounds().ok_or("nothing drawn")?;
    let frame = Frame(PixelFrame::of(scene.mesh(), &opts).ok_or("nothing drawn")?);
    // The framing must reach the ink's edges (lines are drawn on the
    // model's side of an outline): a renderer that frames differently
    // would make every IoU below wrong.
    let ink = ink_box(&image).ok_or("blank drawing")?;
    let want = frame.project([lo[0] as f64, lo[1] as f64, hi[0] as f64, hi[1] as f64]);
    let off = (0..4)
        .map(|k| (ink[k] as f64 - want[k]).abs())
        .fold(0.0, f64::max);
    if off > 1.5 {
        return Err(format!(
            "the framing is off by {off:.1} px (ink {ink:?}, model {want:?})"
        ));
    }
    Ok((image, frame))
}

// ------------------------------------------------------------- the trees

/// A labelled ordered tree, for the edit distance.
#[derive(Clone, Debug)]
struct Tree {
    label: &'static str,
    children: Vec<Tree>,
}

fn leaf(label: &'static str) -> Tree {
    Tree {
        label,
        children: Vec::new(),
    }
}

fn tree(label: &'static str, children: Vec<Tree>) -> Tree {
    Tree { label, children }
}

impl Tree {
    fn size(&self) -> usize {
        1 + self.children.iter().map(Tree::size).sum::<usize>()
    }
    fn from_node(n: &Node) -> Tree {
        tree(n.label, n.children.iter().map(Tree::from_node).collect())
    }
    /// The tree without the top-level bands that hold rafters.
    fn without_rafters(&self) -> Tree {
        let mut t = self.clone();
        t.children
            .retain(|b| b.label != "rafter" && !b.children.iter().any(|c| c.label == "rafter"));
        t
    }
}

/// A band of `n` elements as the generator splits it: each repeat piece
/// is `[] [element] []`, and two empty pieces that meet are one stretch
/// of the layer's back (`other`), as a drawing shows them.
fn band(element: &'static str, n: usize) -> Tree {
    let mut children = vec![leaf("other")];
    for _ in 0..n {
        children.push(leaf(element));
        children.push(leaf("other"));
    }
    tree("other", children)
}

/// A band of `n` elements going round the corners: at each end, beyond
/// the front's row, a side face's first element end-on between two
/// stretches of back.
fn cornered(element: &'static str, n: usize) -> Tree {
    let end = || [leaf("other"), leaf(element), leaf("other")];
    let mut children: Vec<Tree> = end().into();
    children.push(band(element, n.saturating_sub(2)));
    children.extend(end());
    tree("other", children)
}

/// The truth tree in the recogniser's vocabulary, from hall.lsys's splits:
/// the hall's `@SY` from the top (ridge, roof, rafter layer, bracket layer,
/// room, platform; the two layers round the corners); the room's front: the side wall, then columns and bays
/// alternating (`Corridor`'s columns on `Facade`'s bay boundaries), the
/// other side wall; each bay `@SY(flo(1), LINTEL)`: the lintel over the
/// wall of an end bay, or over `@SX` wall, window, wall (`Below`'s middle;
/// its sill and head walls are one wall region with the sides in a
/// drawing) or wall, door, wall (`Door`, its two leaves one door); the
/// platform `@SX(flo(1), CENTRE, flo(1))` with the stairs in the middle.
fn truth_tree(t: &Truth) -> Tree {
    let mut body = vec![leaf("wall"), leaf("column")];
    for p in &t.pieces {
        let below = match p.0 {
            Role::End => leaf("wall"),
            Role::Bay => tree("other", vec![leaf("wall"), leaf("window"), leaf("wall")]),
            Role::Centre => tree("other", vec![leaf("wall"), leaf("door"), leaf("wall")]),
        };
        body.push(tree("bay", vec![leaf("lintel"), below]));
        body.push(leaf("column"));
    }
    body.push(leaf("wall"));
    tree(
        "other",
        vec![
            leaf("ridge"),
            leaf("roof"),
            cornered("rafter", t.rafters),
            cornered("bracket", t.brackets),
            tree("other", body),
            tree(
                "platform",
                vec![leaf("platform"), leaf("stairs"), leaf("platform")],
            ),
        ],
    )
}

/// A tree in postorder: labels, each node's leftmost leaf, the keyroots.
struct Postorder {
    labels: Vec<&'static str>,
    leftmost: Vec<usize>,
    keyroots: Vec<usize>,
}

impl Postorder {
    fn new(t: &Tree) -> Postorder {
        fn walk(t: &Tree, labels: &mut Vec<&'static str>, leftmost: &mut Vec<usize>) -> usize {
            let mut first = None;
            for c in &t.children {
                let l = walk(c, labels, leftmost);
                first.get_or_insert(l);
            }
            let me = labels.len();
            labels.push(t.label);
            leftmost.push(first.unwrap_or(me));
            leftmost[me]
        }
        let (mut labels, mut leftmost) = (Vec::new(), Vec::new());
        walk(t, &mut labels, &mut leftmost);
        // A keyroot: the root, and every node with a left sibling; i.e.
        // the highest node for each leftmost leaf.
        let mut highest = BTreeMap::new();
        for (i, &l) in leftmost.iter().enumerate() {
            highest.insert(l, i);
        }
        let mut keyroots: Vec<usize> = highest.into_values().collect();
        keyroots.sort_unstable();
        Postorder {
            labels,
            leftmost,
            keyroots,
        }
    }
}

/// Zhang and Shasha's tree edit distance (1989): unit costs for inserting,
/// deleting and relabelling a node.
fn edit_distance(a: &Tree, b: &Tree) -> usize {
    let (a, b) = (Postorder::new(a), Postorder::new(b));
    let (n, m) = (a.labels.len(), b.labels.len());
    let mut td = vec![0usize; n * m];
    let mut fd = vec![0usize; (n + 1) * (m + 1)];
    for &i in &a.keyroots {
        for &j in &b.keyroots {
            let (li, lj) = (a.leftmost[i], b.leftmost[j]);
            let (rows, cols) = (i - li + 2, j - lj + 2);
            let at = |x: usize, y: usize| x * cols + y;
            fd[at(0, 0)] = 0;
            for x in 1..rows {
                fd[at(x, 0)] = fd[at(x - 1, 0)] + 1;
            }
            for y in 1..cols {
                fd[at(0, y)] = fd[at(0, y - 1)] + 1;
            }
            for x in 1..rows {
                for y in 1..cols {
                    let (i1, j1) = (li + x - 1, lj + y - 1);
                    let edit = (fd[at(x - 1, y)] + 1).min(fd[at(x, y - 1)] + 1);
                    if a.leftmost[i1] == li && b.leftmost[j1] == lj {
                        let relabel = usize::from(a.labels[i1] != b.labels[j1]);
                        fd[at(x, y)] = edit.min(fd[at(x - 1, y - 1)] + relabel);
                        td[i1 * m + j1] = fd[at(x, y)];
                    } else {
                        let (p, q) = (a.leftmost[i1] - li, b.leftmost[j1] - lj);
                        fd[at(x, y)] = edit.min(fd[at(p, q)] + td[i1 * m + j1]);
                    }
                }
            }
        }
    }
    td[(n - 1) * m + (m - 1)]
}

// ----------------------------------------------------------- measuring

fn count(n: &Node, label: &str) -> usize {
    usize::from(n.label == label) + n.children.iter().map(|c| count(c, label)).sum::<usize>()
}

fn counts(root: &Node) -> Counts {
    Counts {
        bays: count(root, "bay"),
        columns: count(root, "column"),
        doors: count(root, "door"),
        windows: count(root, "window"),
        brackets: count(root, "bracket"),
        rafters: count(root, "rafter"),
    }
}

/// Pixel masks of the truth's boxes, by label.
fn truth_masks(boxes: &[(&str, [f64; 4])], frame: &Frame) -> Vec<Mask> {
    IOU_LABELS
        .iter()
        .map(|label| {
            let mut m = Mask::new(SIZE.0 as usize, SIZE.1 as usize);
            for (_, b) in boxes.iter().filter(|(l, _)| l == label) {
                m.add(frame.project(*b));
            }
            m
        })
        .collect()
}

fn leaf_boxes<'a>(root: &'a Node, label: &str) -> impl Iterator<Item = [f64; 4]> + 'a {
    let label = label.to_string();
    root.leaves()
        .into_iter()
        .filter(move |n| n.label == label)
        .map(|n| n.bbox.map(f64::from))
}

/// One reading of one drawing.
#[derive(Clone, Debug, Default)]
struct Reading {
    /// Why nothing was read.
    error: Option<String>,
    counts: Counts,
    /// By [`IOU_LABELS`]; `None` when neither truth nor reading has any.
    iou: Vec<Option<f64>>,
    distance: usize,
    distance_without_rafters: usize,
    /// The inferred grammar (the width test rebuilds the clean one's).
    grammar: String,
}

/// Everything measured on one drawing.
struct Outcome {
    hall: Hall,
    truth: Counts,
    truth_size: usize,
    truth_size_without_rafters: usize,
    /// By [`CONDITIONS`].
    readings: Vec<Reading>,
}

/// Draws hall `k`, reads it clean and damaged, and compares each reading
/// with the truth; `overlay` is where to write its pictures, if anywhere.
fn measure(k: usize, hall: Hall, fixed: &Fixed, overlay: Option<&Path>) -> Result<Outcome, String> {
    let t = truth(&hall)?;
    let (image, frame) = draw(&hall)?;
    let boxes = truth_boxes(&hall, &t, fixed);
    let masks = truth_masks(&boxes, &frame);
    let want_tree = truth_tree(&t);
    let want_trimmed = want_tree.without_rafters();
    let mut readings = Vec::new();
    for condition in CONDITIONS {
        let picture = damaged(&image, condition, SEED ^ k as u64);
        let name = format!("hall-{k}-{condition}.png");
        let inference = match read_hall(&png_bytes(&picture), &name) {
            Ok(i) => i,
            Err(e) => {
                readings.push(Reading {
                    error: Some(e.to_string()),
                    ..Reading::default()
                });
                continue;
            }
        };
        let root = &inference.tree;
        let iou: Vec<Option<f64>> = IOU_LABELS
            .iter()
            .zip(&masks)
            .map(|(label, want)| {
                let mut got = Mask::new(want.w, want.h);
                leaf_boxes(root, label).for_each(|b| got.add(b));
                want.iou(&got)
            })
            .collect();
        let got_tree = Tree::from_node(root);
        if let Some(dir) = overlay {
            std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
            std::fs::write(dir.join(&name), png_bytes(&picture)).map_err(|e| e.to_string())?;
            let painted = dir.join(format!("hall-{k}-{condition}-overlay.png"));
            paint_overlay(&picture, &masks, root, &painted)?;
        }
        readings.push(Reading {
            error: None,
            counts: counts(root),
            iou,
            distance: edit_distance(&got_tree, &want_tree),
            distance_without_rafters: edit_distance(&got_tree.without_rafters(), &want_trimmed),
            grammar: inference.grammar,
        });
    }
    Ok(Outcome {
        hall,
        truth: t.counts(),
        truth_size: want_tree.size(),
        truth_size_without_rafters: want_trimmed.size(),
        readings,
    })
}

/// The truth's pixels tinted by label over the drawing, the inferred
/// leaves of the same labels outlined in the same colour, darker.
fn paint_overlay(img: &Image, masks: &[Mask], root: &Node, path: &Path) -> Result<(), String> {
    const COLOURS: [[u8; 3]; 7] = [
        [220, 40, 40],
        [40, 160, 40],
        [40, 80, 220],
        [230, 150, 0],
        [150, 40, 200],
        [0, 170, 170],
        [200, 0, 120],
    ];
    let mut out = img.clone();
    let w = img.width as usize;
    for (mask, c) in masks.iter().zip(COLOURS) {
        for (i, _) in mask.on.iter().enumerate().filter(|(_, on)| **on) {
            for (k, &ck) in c.iter().enumerate() {
                let p = &mut out.rgb[i * 3 + k];
                *p = ((*p as u16 + ck as u16) / 2) as u8;
            }
        }
    }
    for (label, c) in IOU_LABELS.iter().zip(COLOURS) {
        for b in leaf_boxes(root, label) {
            let [x0, y0, x1, y1] = b.map(|v| v as usize);
            let dark = c.map(|v| v / 2);
            let mut put = |x: usize, y: usize| {
                if x < w && y < img.height as usize {
                    out.rgb[(y * w + x) * 3..(y * w + x) * 3 + 3].copy_from_slice(&dark);
                }
            };
            for x in x0..x1 {
                put(x, y0);
                put(x, y1.saturating_sub(1));
            }
            for y in y0..y1 {
                put(x0, y);
                put(x1.saturating_sub(1), y);
            }
        }
    }
    std::fs::write(path, png_bytes(&out)).map_err(|e| e.to_string())
}

// ------------------------------------------------------- the width test

/// What the inferred grammar builds at width `w`, counted by the
/// generator's own functions on its `#define`s: `@RSX(END, BAY, CENTRE)`
/// for the bays (a column on every boundary; each role's fill from its
/// `E_`, `B_`, `C_` `DOOR` or `WIN` define) and `@RX(BRK_PITCH)` for the
/// bracket sets.
fn rebuilt_counts(grammar: &str, w: f64) -> Result<Counts, String> {
    let defines: BTreeMap<&str, f64> = grammar
        .lines()
        .filter_map(|l| {
            let mut words = l.strip_prefix("#define ")?.split_whitespace();
            Some((words.next()?, words.next()?.parse().ok()?))
        })
        .collect();
    let get = |n: &str| {
        defines
            .get(n)
            .copied()
            .ok_or_else(|| format!("no #define {n}"))
    };
    let pieces =
        symmetric(w, get("END")?, get("BAY")?, get("CENTRE")?, Axis::X).map_err(|e| e.problem)?;
    let fill = |r: Role, kind: &str| {
        let p = match r {
            Role::End => "E",
            Role::Bay => "B",
            Role::Centre => "C",
        };
        defines.contains_key(format!("{p}_{kind}").as_str())
    };
    // A row of `rule` (`Brackets`, `Rafters`) repeats its element every
    // `pitch`; on all four faces (`@Comp [BrkFace] [BrkFace] ...`), a side's
    // first shows end-on at each end. No rule: none.
    let row = |rule: &str, face: &str, pitch: &str| -> Result<usize, String> {
        if !grammar.contains(&format!("\n{rule} -->")) {
            return Ok(0);
        }
        let corners = if grammar.contains(&format!("@Comp [{face}] [{face}]")) {
            2
        } else {
            0
        };
        Ok(repeat(w, get(pitch)?, Axis::X)
            .map_err(|e| e.problem)?
            .len()
            + corners)
    };
    let brackets = row("Brackets", "BrkFace", "BRK_PITCH")?;
    let rafters = row("Rafters", "RafFace", "RAF_PITCH")?;
    Ok(Counts {
        bays: pieces.len(),
        columns: pieces.len() + 1,
        doors: pieces.iter().filter(|p| fill(p.0, "DOOR")).count(),
        windows: pieces.iter().filter(|p| fill(p.0, "WIN")).count(),
        brackets,
        rafters,
    })
}

struct WidthCase {
    drawing: usize,
    /// Which of [`CONDITIONS`] the grammar was read from.
    condition: usize,
    factor: f64,
    inferred_w: f64,
    got: Result<Counts, String>,
    want: Counts,
    /// The least and the most of each count that halls drawing the same
    /// picture build at this factor ([`picture_range`]).
    lo: Counts,
    hi: Counts,
}

/// Nominal sizes tried inside each interval of [`picture_range`].
const RANGE_SAMPLES: usize = 4000;

/// `RANGE_SAMPLES` values strictly inside `(lo, hi)`, and `hi`.
fn inside(lo: f64, hi: f64) -> impl Iterator<Item = f64> {
    let step = (hi - lo) / (RANGE_SAMPLES + 1) as f64;
    (1..=RANGE_SAMPLES)
        .map(move |k| lo + step * k as f64)
        .chain([hi])
}

/// The counts that halls drawing the same picture as `h` build at `h`'s
/// width × `factor`, least and most. A drawing shows the bays stretched
/// to inner/(2n) (inner = W - 2 END - CENTRE), which every nominal BAY'
/// in (inner/(2n+2), inner/(2n)] lays out alike (any BAY' above inner/2
/// for n = 0), and the bracket sets stretched to W/m, which every pitch
/// in (W/(m+1), W/m] lays out alike; each such hall, `h` but for BAY'
/// (or the pitch), is built by the generator's own [`truth`] at the
/// factor. Every value tried is checked to draw `h`'s picture.
fn picture_range(h: &Hall, factor: f64) -> Result<(Counts, Counts), String> {
    let w = h.get("W");
    let t = truth(h)?;
    let n = t.pieces.iter().filter(|p| p.0 == Role::Bay).count() / 2;
    let inner = w - 2.0 * h.get("END") - h.get("CENTRE");
    let bays = if n == 0 {
        // Past the widest factor's inner/2 every BAY' lays out none.
        let widest = FACTORS.iter().copied().fold(1.0, f64::max);
        (inner / 2.0, w * widest)
    } else {
        (inner / (2 * n + 2) as f64, inner / (2 * n) as f64)
    };
    let m = t.brackets - 2;
    let pitches = (w / (m + 1) as f64, w / m as f64);
    let at = h.with_width(w * factor);
    let mut built = Vec::new();
    for bay in inside(bays.0, bays.1) {
        if truth(&h.with("BAY", bay))?.pieces != t.pieces {
            return Err(format!("BAY {bay} draws another picture"));
        }
        built.push(truth(&at.with("BAY", bay))?.counts());
    }
    let mut sets = Vec::new();
    for pitch in inside(pitches.0, pitches.1) {
        if truth_pitched(h, pitch)?.brackets != t.brackets {
            return Err(format!("bracket pitch {pitch} draws another picture"));
        }
        sets.push(truth_pitched(&at, pitch)?.brackets);
    }
    // The rafters: every pitch in (W/(r+1), W/r] for r on the front lays
    // them out alike; the generator's rafters are the front's and a side
    // face's first at each end.
    let r = t.rafters - 2;
    let mut rafters = Vec::new();
    for pitch in inside(w / (r + 1) as f64, w / r as f64) {
        if repeat(w, pitch, Axis::X).map_err(|e| e.problem)?.len() != r {
            return Err(format!("rafter pitch {pitch} draws another picture"));
        }
        rafters.push(
            repeat(w * factor, pitch, Axis::X)
                .map_err(|e| e.problem)?
                .len()
                + 2,
        );
    }
    let least = |f: fn(&Counts) -> usize| built.iter().map(f).min().unwrap_or(0);
    let most = |f: fn(&Counts) -> usize| built.iter().map(f).max().unwrap_or(0);
    let lo = Counts {
        bays: least(|c| c.bays),
        columns: least(|c| c.columns),
        doors: least(|c| c.doors),
        windows: least(|c| c.windows),
        brackets: sets.iter().copied().min().unwrap_or(0),
        rafters: rafters.iter().copied().min().unwrap_or(0),
    };
    let hi = Counts {
        bays: most(|c| c.bays),
        columns: most(|c| c.columns),
        doors: most(|c| c.doors),
        windows: most(|c| c.windows),
        brackets: sets.iter().copied().max().unwrap_or(0),
        rafters: rafters.iter().copied().max().unwrap_or(0),
    };
    Ok((lo, hi))
}

fn width_test(outcomes: &[(usize, Outcome)]) -> Vec<WidthCase> {
    let mut cases = Vec::new();
    let eligible = outcomes.iter().filter(|(_, o)| {
        o.readings[0].error.is_none()
            && FACTORS
                .iter()
                .all(|f| truth(&o.hall.with_width(o.hall.get("W") * f)).is_ok())
    });
    for (k, o) in eligible.take(WIDTH_DRAWINGS) {
        for f in FACTORS {
            let want = truth(&o.hall.with_width(o.hall.get("W") * f))
                .expect("checked above")
                .counts();
            let (lo, hi) =
                picture_range(&o.hall, f).unwrap_or_else(|e| panic!("drawing {k} at {f}: {e}"));
            assert!(
                (0..5).all(|i| (lo.five()[i]..=hi.five()[i]).contains(&want.five()[i])),
                "drawing {k} at {f}: the generator's own count outside its range"
            );
            // The same drawing read clean and damaged: each reading's grammar.
            for (condition, reading) in o.readings.iter().enumerate() {
                let grammar = &reading.grammar;
                let inferred_w = grammar
                    .lines()
                    .find_map(|l| l.strip_prefix("#define W "))
                    .and_then(|l| l.split_whitespace().next())
                    .and_then(|v| v.parse::<f64>().ok())
                    .unwrap_or(f64::NAN);
                let got = match &reading.error {
                    Some(e) => Err(format!("unread: {e}")),
                    None => rebuilt_counts(grammar, inferred_w * f),
                };
                cases.push(WidthCase {
                    drawing: *k,
                    condition,
                    factor: f,
                    inferred_w,
                    got,
                    want,
                    lo,
                    hi,
                });
            }
        }
    }
    cases
}

// ------------------------------------------------------------ the report

fn pct(n: usize, of: usize) -> String {
    if of == 0 {
        "–".into()
    } else {
        format!("{:.1} %", 100.0 * n as f64 / of as f64)
    }
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

fn median(v: &[f64]) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => (v[n / 2 - 1] + v[n / 2]) / 2.0,
    }
}

fn five(c: &Counts) -> String {
    c.five()
        .iter()
        .map(|n| n.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Which of the five counts differ, `name got/expected`.
fn differences(got: &Counts, want: &Counts) -> String {
    COUNT_NAMES
        .iter()
        .zip(got.five().iter().zip(want.five()))
        .filter(|(_, (g, w))| **g != *w)
        .map(|(n, (g, w))| format!("{n} {g}/{w}"))
        .collect::<Vec<_>>()
        .join("; ")
}

/// A width case's five ranges, `lo–hi` or one number.
fn ranges(c: &WidthCase) -> String {
    c.lo.five()
        .iter()
        .zip(c.hi.five())
        .map(|(lo, hi)| span(*lo, hi))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `lo–hi`, or one number when they are equal.
fn span(lo: usize, hi: usize) -> String {
    if lo == hi {
        lo.to_string()
    } else {
        format!("{lo}–{hi}")
    }
}

/// Which of the five counts lie outside their range, `name got ∉ lo–hi`.
fn out_of_range(got: &Counts, c: &WidthCase) -> String {
    COUNT_NAMES
        .iter()
        .enumerate()
        .filter(|(i, _)| !(c.lo.five()[*i]..=c.hi.five()[*i]).contains(&got.five()[*i]))
        .map(|(i, n)| {
            format!(
                "{n} {} ∉ {}",
                got.five()[i],
                span(c.lo.five()[i], c.hi.five()[i])
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

struct Run {
    count: usize,
    seed: u64,
    command: String,
    skipped: Vec<(usize, Hall, String)>,
    outcomes: Vec<(usize, Outcome)>,
    width: Vec<WidthCase>,
}

fn report(run: &Run) -> String {
    let mut s = String::new();
    let outs = &run.outcomes;
    let _ = writeln!(s, "# The drawing round trip, measured\n");
    let _ = writeln!(
        s,
        "Generated by `{}` ([examples/drawing_roundtrip.rs](../examples/drawing_roundtrip.rs)); \
         every number below comes from that run. {} halls sampled with seed {}, {} drawn and read.\n",
        run.command,
        run.count,
        run.seed,
        outs.len()
    );
    let _ = writeln!(s, "## How\n");
    // The hall's own `#define`s with a number for a value, in their order.
    let text = std::fs::read_to_string(HALL_SIZES).unwrap_or_default();
    let file_defines: Vec<(&str, &str)> = text
        .lines()
        .filter_map(|l| {
            let mut w = l.strip_prefix("#define ")?.split_whitespace();
            let (name, value) = (w.next()?, w.next()?);
            value.parse::<f64>().is_ok().then_some((name, value))
        })
        .collect();
    let kept: Vec<String> = file_defines
        .iter()
        .filter(|(n, _)| !PARAMS.iter().any(|p| p.0 == *n))
        .map(|(n, v)| format!("{n} {v}"))
        .collect();
    let _ = writeln!(
        s,
        "* **Halls.** `examples/shapes/hall.lsys` with these `#define`s drawn uniformly \
         (splitmix64, seed {}) and rounded to 0.01; the others keep the file's values \
         ({}).\n",
        run.seed,
        kept.join(", ")
    );
    let _ = writeln!(
        s,
        "  | define | from | to | hall.lsys |\n  |---|---|---|---|"
    );
    for (name, lo, hi) in PARAMS {
        let default = file_defines
            .iter()
            .find(|(n, _)| *n == name)
            .map_or("", |d| d.1);
        let _ = writeln!(s, "  | {name} | {lo} | {hi} | {default} |");
    }
    let _ = writeln!(
        s,
        "\n* **Drawings.** Each hall built and drawn by the library calls `lsys render \
         examples/shapes/hall.lsys --view front --style lines --size {w}x{h} -D ...` makes \
         (the file's derivation length, {ss} × {ss} supersampling), and read by `lsys::driver::infer_edited`, as `lsys infer` reads them, with \
         its defaults (`--gap {gap}`); a hall read as a Pailou's front (the driver reads those by \
         synthesis, [drawing-roundtrip-pailou.md](drawing-roundtrip-pailou.md)) counts as unread.",
        w = SIZE.0,
        h = SIZE.1,
        ss = render_options().supersample,
        gap = InferOptions::default().gap,
    );
    let _ = writeln!(
        s,
        "* **Damage.** As `tests/infer.rs` damages its W=24 drawing: *gaps*, 3 pixels of every \
         40 erased across every line; *jitter*, each 8-pixel stretch of rows (columns) of ink \
         shifted by −1, 0 or +1 pixel (seeded per drawing); *blur*, each pixel the mean of its \
         3 × 3 neighbourhood."
    );
    let _ = writeln!(
        s,
        "* **Counts.** The truth is the turtle's own `symmetric` and `repeat` \
         (`lsys::internals::turtle::scope`) on the sampled sizes: bays `@RSX(END, BAY, CENTRE)`, \
         a column on each of their boundaries, the door in the centre bay, a window in every \
         other bay but the two ends, bracket sets `@RX({BRK_PITCH})`, rafters \
         `@RX({RAF_PITCH})`. A drawing counts as right for a label when the inferred tree has \
         exactly that many nodes so labelled."
    );
    let _ = writeln!(
        s,
        "* **IoU.** Truth boxes in metres from hall.lsys's splits: columns COL wide centred on \
         the bay boundaries, PLAT to PLAT + ROOM; windows {WINDOW_SIDE} in from their bay's \
         sides, {WINDOW_SILL} above its floor and {WINDOW_HEAD} under its lintel; the door the \
         middle {DOOR_FRAC} of the centre bay, floor to lintel; bracket sets {} wide in the \
         middle of each `@RX({BRK_PITCH})` piece, the top {} of the layer; the roof OV beyond \
         the facade each side, ROOF high; the platform {PLAT_OV} beyond it, the stairs CENTRE \
         wide in its middle. They are projected to pixels with the renderer's own framing \
         (`export::render::PixelFrame`: the model fills the picture less 5 % a side, \
         centred, one scale), and every drawing is checked: the model's box lands on the \
         ink's edges within 1.5 pixels. Per label, IoU = |truth ∩ inferred| / \
         |truth ∪ inferred| over the pixels of the union of the truth boxes and the union of \
         the inferred leaves with that label, averaged over the drawings where either has any \
         (n).",
        BRK_SET.0, BRK_SET.1,
    );
    let _ = writeln!(
        s,
        "* **Tree edit distance.** Zhang–Shasha with unit costs (insert, delete, relabel) \
         between the inferred tree and the generator's split structure in the same \
         vocabulary: the root `other` over ridge, roof, the rafter band (`other`: back, \
         rafter, back, ..., back; back = `other`), the bracket band (the same with \
         bracket), the body (`other`: wall, column, bay, column, ..., bay, column, wall; an \
         end bay is lintel + wall, another bay lintel + `other`(wall, window, wall), the \
         centre bay lintel + `other`(wall, door, wall)) and the platform (platform, stairs, \
         platform). Normalised = distance / nodes of the truth tree. \"Without rafters\" \
         drops the top-level band holding rafters from both trees."
    );
    let _ = writeln!(
        s,
        "* **Width test.** The grammar inferred from each of the first {WIDTH_DRAWINGS} clean \
         drawings that were read and whose generator builds at all four widths, built at `W` = \
         its inferred W × factor, against the generator at the sampled W × factor. What the \
         inferred grammar builds is counted by the same `symmetric` and `repeat` applied to \
         its `#define`s (W, END, BAY, CENTRE, BRK_PITCH, RAF_PITCH; each bay kind's fill from \
         its `E_`, `B_`, `C_` `DOOR` or `WIN`), which is what its `@RSX` and `@RX` splits \
         compute when built; a grammar without a `Brackets` (`Rafters`) rule builds 0 bracket \
         sets (rafters). A drawing shows \
         the bays stretched to inner/(2n) (inner = W − 2 END − CENTRE, n bays a side), and \
         every hall that differs from the sampled one only in a nominal BAY' in \
         (inner/(2n+2), inner/(2n)] (above inner/2 when n = 0) draws the same picture; so \
         does every bracket pitch in (W/(m+1), W/m] for m sets on the front, and every rafter \
         pitch in (W/(r+1), W/r] for r rafters on the front. The *range* \
         [lo, hi] of a count is the least and most the generator builds at W × factor over \
         those halls (its own `symmetric` and `repeat` on {RANGE_SAMPLES} values strictly \
         inside each interval and its closed end, each checked to draw the same picture). A \
         rebuild is *consistent* when its count lies in the range; a count is *determined* \
         when lo = hi, and only there must a reader that reads the drawing right match the \
         generator.\n"
    );

    // Counts.
    let _ = writeln!(s, "## Exact counts\n");
    let _ = writeln!(
        s,
        "Share of drawings read with exactly the generator's count (\"all five\": bays, \
         columns, doors, windows and bracket sets at once). Unread: the reader refused the \
         drawing.\n"
    );
    let _ = writeln!(
        s,
        "| drawing | n | unread | bays | columns | doors | windows | bracket sets | all five | rafters |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
    for (c, condition) in CONDITIONS.iter().enumerate() {
        let n = outs.len();
        let unread = outs
            .iter()
            .filter(|(_, o)| o.readings[c].error.is_some())
            .count();
        let right = |f: &dyn Fn(&Counts, &Counts) -> bool| {
            pct(
                outs.iter()
                    .filter(|(_, o)| {
                        o.readings[c].error.is_none() && f(&o.readings[c].counts, &o.truth)
                    })
                    .count(),
                n,
            )
        };
        let cols: Vec<String> = (0..5)
            .map(|i| right(&|g: &Counts, w: &Counts| g.five()[i] == w.five()[i]))
            .collect();
        let _ = writeln!(
            s,
            "| {condition} | {n} | {unread} | {} | {} | {} |",
            cols.join(" | "),
            right(&|g, w| g.five() == w.five()),
            right(&|g, w| g.rafters == w.rafters)
        );
    }

    // IoU.
    let _ = writeln!(s, "\n## IoU per label\n");
    let _ = writeln!(
        s,
        "Mean over drawings (n where it is not {}).\n",
        outs.len()
    );
    let _ = writeln!(s, "| drawing | {} |", IOU_LABELS.join(" | "));
    let _ = writeln!(s, "|---|{}", "---|".repeat(IOU_LABELS.len()));
    // The last row: the clean drawings read with all five counts right,
    // where the boxes are measured apart from the recognition's misses.
    let rows = CONDITIONS
        .iter()
        .enumerate()
        .map(|(c, name)| (c, name.to_string(), false))
        .chain([(0, "clean, all five counts right".to_string(), true)]);
    for (c, name, right_only) in rows {
        let read: Vec<&Outcome> = outs
            .iter()
            .map(|(_, o)| o)
            .filter(|o| o.readings[c].error.is_none())
            .filter(|o| !right_only || o.readings[c].counts.five() == o.truth.five())
            .collect();
        let cells: Vec<String> = (0..IOU_LABELS.len())
            .map(|l| {
                let v: Vec<f64> = read.iter().filter_map(|o| o.readings[c].iou[l]).collect();
                if v.len() == outs.len() {
                    format!("{:.3}", mean(&v))
                } else {
                    format!("{:.3} (n {})", mean(&v), v.len())
                }
            })
            .collect();
        let _ = writeln!(s, "| {name} | {} |", cells.join(" | "));
    }
    let _ = writeln!(s, "\nThe three lowest per label, clean drawings:\n");
    let _ = writeln!(
        s,
        "| label | drawing | IoU | parameters |\n|---|---|---|---|"
    );
    for (l, label) in IOU_LABELS.iter().enumerate() {
        let mut v: Vec<(f64, usize, &Hall)> = outs
            .iter()
            .filter_map(|(k, o)| {
                o.readings[0]
                    .iou
                    .get(l)
                    .copied()
                    .flatten()
                    .map(|x| (x, *k, &o.hall))
            })
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (x, k, h) in v.iter().take(3) {
            let _ = writeln!(s, "| {label} | {k} | {x:.3} | {} |", h.shown());
        }
    }

    // Tree edit distance.
    let _ = writeln!(s, "\n## Tree edit distance\n");
    let sizes: Vec<f64> = outs.iter().map(|(_, o)| o.truth_size as f64).collect();
    let trimmed: Vec<f64> = outs
        .iter()
        .map(|(_, o)| o.truth_size_without_rafters as f64)
        .collect();
    let _ = writeln!(
        s,
        "Truth trees have {:.1} nodes on average (median {:.0}), {:.1} without the rafter band.\n",
        mean(&sizes),
        median(&sizes),
        mean(&trimmed)
    );
    let _ = writeln!(
        s,
        "| drawing | n | mean | median | mean normalised | without rafters: mean | median | mean normalised |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for (c, condition) in CONDITIONS.iter().enumerate() {
        let read: Vec<&Outcome> = outs
            .iter()
            .map(|(_, o)| o)
            .filter(|o| o.readings[c].error.is_none())
            .collect();
        let d: Vec<f64> = read.iter().map(|o| o.readings[c].distance as f64).collect();
        let dn: Vec<f64> = read
            .iter()
            .map(|o| o.readings[c].distance as f64 / o.truth_size as f64)
            .collect();
        let t: Vec<f64> = read
            .iter()
            .map(|o| o.readings[c].distance_without_rafters as f64)
            .collect();
        let tn: Vec<f64> = read
            .iter()
            .map(|o| {
                o.readings[c].distance_without_rafters as f64 / o.truth_size_without_rafters as f64
            })
            .collect();
        let _ = writeln!(
            s,
            "| {condition} | {} | {:.1} | {:.1} | {:.3} | {:.1} | {:.1} | {:.3} |",
            read.len(),
            mean(&d),
            median(&d),
            mean(&dn),
            mean(&t),
            median(&t),
            mean(&tn)
        );
    }

    // Width test.
    let _ = writeln!(s, "\n## Width test\n");
    let clean: Vec<&WidthCase> = run.width.iter().filter(|c| c.condition == 0).collect();
    let drawings: std::collections::BTreeSet<usize> = clean.iter().map(|c| c.drawing).collect();
    let _ = writeln!(
        s,
        "{} grammars (drawings {}), each rebuilt at four widths. Share of rebuilds with the \
         generator's count at that width.\n",
        drawings.len(),
        drawings
            .iter()
            .map(|d| d.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(
        s,
        "| factor | n | bays | columns | doors | windows | bracket sets ±0 | bracket sets ±1 | all (bracket sets ±1) |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
    for f in FACTORS {
        let cases: Vec<&WidthCase> = clean.iter().copied().filter(|c| c.factor == f).collect();
        let share = |p: &dyn Fn(&Counts, &Counts) -> bool| {
            pct(
                cases
                    .iter()
                    .filter(|c| c.got.as_ref().is_ok_and(|g| p(g, &c.want)))
                    .count(),
                cases.len(),
            )
        };
        let _ = writeln!(
            s,
            "| {f} | {} | {} | {} | {} | {} | {} | {} | {} |",
            cases.len(),
            share(&|g, w| g.bays == w.bays),
            share(&|g, w| g.columns == w.columns),
            share(&|g, w| g.doors == w.doors),
            share(&|g, w| g.windows == w.windows),
            share(&|g, w| g.brackets == w.brackets),
            share(&|g, w| g.brackets.abs_diff(w.brackets) <= 1),
            share(&|g, w| g.five()[..4] == w.five()[..4] && g.brackets.abs_diff(w.brackets) <= 1),
        );
    }

    let _ = writeln!(
        s,
        "\nThe same rebuilds against the range of counts that halls drawing the same picture \
         give at that factor (How, *Width test*): consistent, the count within [lo, hi]; \
         determined, lo = hi (the drawing fixes the count); exact when determined, the count \
         right among those (k of n). \"All four\": bays, columns, windows and bracket sets at \
         once (exact ±0; determined: the bays' and the bracket sets' ranges both one count).\n"
    );
    let _ = writeln!(
        s,
        "| factor | count | exact | consistent | determined | exact when determined |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    // Bays, columns, windows, bracket sets, rafters: their places in `six()`.
    let ranged: [(&str, &[usize]); 6] = [
        ("bays", &[0]),
        ("columns", &[1]),
        ("windows", &[3]),
        ("bracket sets", &[4]),
        ("rafters", &[5]),
        ("all four", &[0, 1, 3, 4]),
    ];
    for f in FACTORS {
        let cases: Vec<&WidthCase> = clean.iter().copied().filter(|c| c.factor == f).collect();
        for (name, idx) in ranged {
            let exact = |c: &WidthCase| {
                c.got
                    .as_ref()
                    .is_ok_and(|g| idx.iter().all(|&i| g.six()[i] == c.want.six()[i]))
            };
            let within = |c: &&&WidthCase| {
                c.got.as_ref().is_ok_and(|g| {
                    idx.iter()
                        .all(|&i| (c.lo.six()[i]..=c.hi.six()[i]).contains(&g.six()[i]))
                })
            };
            let determined: Vec<&&WidthCase> = cases
                .iter()
                .filter(|c| idx.iter().all(|&i| c.lo.six()[i] == c.hi.six()[i]))
                .collect();
            let right = determined.iter().filter(|c| exact(c)).count();
            let _ = writeln!(
                s,
                "| {f} | {name} | {} | {} | {} ({}) | {} ({right} of {}) |",
                pct(cases.iter().filter(|c| exact(c)).count(), cases.len()),
                pct(cases.iter().filter(within).count(), cases.len()),
                pct(determined.len(), cases.len()),
                determined.len(),
                pct(right, determined.len()),
                determined.len()
            );
        }
    }

    // The width test on the damaged drawings' grammars.
    let _ = writeln!(
        s,
        "\nThe same {} drawings read after each damage (How, *Damage*), their grammars rebuilt \
         the same way: share of rebuilds consistent with the picture (the count within [lo, hi]; \
         an unread drawing counts as not), and in brackets exact (the generator's count).\n",
        drawings.len()
    );
    let _ = writeln!(
        s,
        "| drawing | factor | n | bays | columns | windows | bracket sets | rafters | all four |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
    for (condition, name) in CONDITIONS.iter().enumerate() {
        for f in FACTORS {
            let cases: Vec<&WidthCase> = run
                .width
                .iter()
                .filter(|c| c.condition == condition && c.factor == f)
                .collect();
            let cell = |idx: &[usize]| {
                let within = cases
                    .iter()
                    .filter(|c| {
                        c.got.as_ref().is_ok_and(|g| {
                            idx.iter()
                                .all(|&i| (c.lo.six()[i]..=c.hi.six()[i]).contains(&g.six()[i]))
                        })
                    })
                    .count();
                let exact = cases
                    .iter()
                    .filter(|c| {
                        c.got
                            .as_ref()
                            .is_ok_and(|g| idx.iter().all(|&i| g.six()[i] == c.want.six()[i]))
                    })
                    .count();
                format!("{} ({})", pct(within, cases.len()), pct(exact, cases.len()))
            };
            let _ = writeln!(
                s,
                "| {name} | {f} | {} | {} | {} | {} | {} | {} | {} |",
                cases.len(),
                cell(&[0]),
                cell(&[1]),
                cell(&[3]),
                cell(&[4]),
                cell(&[5]),
                cell(&[0, 1, 3, 4]),
            );
        }
    }

    // Failures.
    let _ = writeln!(s, "\n## Failures\n");
    if !run.skipped.is_empty() {
        let _ = writeln!(s, "Halls not drawn:\n");
        for (k, h, why) in &run.skipped {
            let _ = writeln!(s, "* {k}: {} — {why}", h.shown());
        }
        let _ = writeln!(s);
    }
    // How many drawings got each count wrong, before the lists.
    let _ = writeln!(
        s,
        "Drawings read wrong, and how many of them have each count wrong (a drawing may have \
         several):\n"
    );
    let _ = writeln!(
        s,
        "| drawing | wrong | unread | {} | only bracket sets |",
        COUNT_NAMES.join(" | ")
    );
    let _ = writeln!(s, "|---|---|---|{}---|", "---|".repeat(COUNT_NAMES.len()));
    for (c, condition) in CONDITIONS.iter().enumerate() {
        let read = |o: &Outcome| o.readings[c].error.is_none();
        let differs = |o: &Outcome, i: usize| o.readings[c].counts.five()[i] != o.truth.five()[i];
        let wrong = outs
            .iter()
            .filter(|(_, o)| !read(o) || o.readings[c].counts.five() != o.truth.five())
            .count();
        let unread = outs.iter().filter(|(_, o)| !read(o)).count();
        let per: Vec<String> = (0..COUNT_NAMES.len())
            .map(|i| {
                outs.iter()
                    .filter(|(_, o)| read(o) && differs(o, i))
                    .count()
                    .to_string()
            })
            .collect();
        let only_brackets = outs
            .iter()
            .filter(|(_, o)| read(o) && differs(o, 4) && (0..4).all(|i| !differs(o, i)))
            .count();
        let _ = writeln!(
            s,
            "| {condition} | {wrong} | {unread} | {} | {only_brackets} |",
            per.join(" | ")
        );
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "Counts as got / expected, in the order bays, columns, doors, windows, bracket sets. \
         Damaged drawings are listed when their clean drawing was read right. Redraw one with \
         `lsys render examples/shapes/hall.lsys --view front --style lines --size 1000x600` \
         and a `-D` for each parameter.\n"
    );
    for (c, condition) in CONDITIONS.iter().enumerate() {
        let failed: Vec<&(usize, Outcome)> = outs
            .iter()
            .filter(|(_, o)| {
                let r = &o.readings[c];
                let wrong = r.error.is_some() || r.counts.five() != o.truth.five();
                let clean_right = c == 0
                    || (o.readings[0].error.is_none()
                        && o.readings[0].counts.five() == o.truth.five());
                wrong && clean_right
            })
            .collect();
        let _ = writeln!(s, "### {condition} ({})\n", failed.len());
        if failed.is_empty() {
            continue;
        }
        let _ = writeln!(s, "| drawing | parameters | got | expected | differs |");
        let _ = writeln!(s, "|---|---|---|---|---|");
        for (k, o) in failed {
            let r = &o.readings[c];
            let (got, diff) = match &r.error {
                Some(e) => (format!("not read: {e}"), String::new()),
                None => (five(&r.counts), differences(&r.counts, &o.truth)),
            };
            let _ = writeln!(
                s,
                "| {k} | {} | {got} | {} | {diff} |",
                o.hall.shown(),
                five(&o.truth)
            );
        }
        let _ = writeln!(s);
    }
    let failed: Vec<&WidthCase> = run
        .width
        .iter()
        .filter(|c| c.condition == 0)
        .filter(|c| match &c.got {
            Ok(g) => {
                g.five()[..4] != c.want.five()[..4]
                    || g.brackets.abs_diff(c.want.brackets) > 1
                    || !out_of_range(g, c).is_empty()
            }
            Err(_) => true,
        })
        .collect();
    let _ = writeln!(s, "### width test ({})\n", failed.len());
    if !failed.is_empty() {
        let _ = writeln!(
            s,
            "Rebuilds with a count other than the generator's (bracket sets: off by more than \
             one) or outside its range. Range: each count's [lo, hi] over the halls that draw \
             the same picture (lo–hi, or one number when determined). Outside range: the \
             counts the reader got wrong beyond what the drawing leaves open.\n"
        );
        let _ = writeln!(
            s,
            "| drawing | factor | sampled W | inferred W | parameters | rebuilt | generator | differs | range | outside range |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
        for c in failed {
            let o = &outs
                .iter()
                .find(|(k, _)| *k == c.drawing)
                .expect("a drawing")
                .1;
            let (got, diff, outside) = match &c.got {
                Ok(g) => (five(g), differences(g, &c.want), out_of_range(g, c)),
                Err(e) => (format!("does not build: {e}"), String::new(), String::new()),
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {got} | {} | {diff} | {} | {outside} |",
                c.drawing,
                c.factor,
                o.hall.get("W"),
                c.inferred_w,
                o.hall.shown(),
                five(&c.want),
                ranges(c)
            );
        }
    }
    s
}

const USAGE: &str = "usage: cargo run --release --example drawing_roundtrip -- [--quick] [--count N] [--seed S] [--out FILE] [--overlay DIR [--drawing K]]";

fn main() {
    let mut args = std::env::args().skip(1);
    let (mut count, mut seed, mut out, mut quick) = (FULL, SEED, None, false);
    let (mut overlay, mut shown) = (None, 0);
    while let Some(a) = args.next() {
        let mut value = |what: &str| args.next().unwrap_or_else(|| panic!("{a} needs {what}"));
        match a.as_str() {
            "--quick" => {
                quick = true;
                count = QUICK;
            }
            "--count" => count = value("a number").parse().expect("--count N"),
            "--seed" => seed = value("a number").parse().expect("--seed S"),
            "--out" => out = Some(PathBuf::from(value("a file"))),
            "--overlay" => overlay = Some(PathBuf::from(value("a folder"))),
            "--drawing" => shown = value("a number").parse().expect("--drawing K"),
            "--help" | "-h" => {
                println!("{USAGE}");
                return;
            }
            other => {
                eprintln!("drawing_roundtrip: unknown argument {other:?}\n{USAGE}");
                std::process::exit(2);
            }
        }
    }
    // The full run rewrites the document; a quick one prints unless told.
    let out = out.or_else(|| (!quick).then(|| PathBuf::from(DOC)));
    // The edit distance on the example of Zhang and Shasha's paper (Fig. 2).
    let paper_a = tree(
        "f",
        vec![
            tree("d", vec![leaf("a"), tree("c", vec![leaf("b")])]),
            leaf("e"),
        ],
    );
    let paper_b = tree(
        "f",
        vec![
            tree("c", vec![tree("d", vec![leaf("a"), leaf("b")])]),
            leaf("e"),
        ],
    );
    assert_eq!(edit_distance(&paper_a, &paper_b), 2, "Zhang–Shasha");

    let fixed =
        read_fixed(&std::fs::read_to_string(HALL_SIZES).expect("examples/shapes/hall_parts.lsys"));
    let mut rng = SplitMix(seed);
    let halls: Vec<Hall> = (0..count).map(|_| Hall::sample(&mut rng)).collect();
    let started = Instant::now();
    let results = measure_all("drawing_roundtrip", count, |k| {
        let pictures = overlay.as_deref().filter(|_| k == shown);
        measure(k, halls[k], &fixed, pictures)
    });
    let mut outcomes = Vec::new();
    let mut skipped = Vec::new();
    for (k, r) in results.into_iter().enumerate() {
        match r {
            Ok(o) => outcomes.push((k, o)),
            // A framing mismatch means the truth cannot be placed: stop.
            Err(e) if e.contains("framing") => panic!("drawing {k}: {e}"),
            Err(e) => skipped.push((k, halls[k], e)),
        }
    }
    let width = width_test(&outcomes);
    let mut command = "cargo run --release --example drawing_roundtrip".to_string();
    if quick || count != FULL || seed != SEED {
        command.push_str(" --");
        if quick {
            command.push_str(" --quick");
        }
        if count != FULL && !(quick && count == QUICK) {
            let _ = write!(command, " --count {count}");
        }
        if seed != SEED {
            let _ = write!(command, " --seed {seed}");
        }
    }
    let text = report(&Run {
        count,
        seed,
        command,
        skipped,
        outcomes,
        width,
    });
    match out {
        Some(path) => {
            std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            eprintln!(
                "drawing_roundtrip: wrote {} in {:.0} s",
                path.display(),
                started.elapsed().as_secs_f64()
            );
        }
        None => print!("{text}"),
    }
}
