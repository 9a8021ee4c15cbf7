//! A Pailou's front read by synthesis: a line drawing whose ground pillars
//! stand free ([`PailouFront`]) -> the style NP-NE-NR and type that draw
//! it, the std:pailou grammar with the measured proportions, and a tree
//! of its parts.
//!
//! Seed 003 reads halls; a Pailou's front has pillars on bases, entrances
//! at several heights and roofs at several levels, which alternating cuts
//! of the drawing do not separate. What the drawing fixes is read
//! directly: the number of ground pillars (so NE = NP - 1 ground
//! entrances) and their places (each entrance's width, so αSide of each
//! entrance: `side[i]`). What it shows but does not measure easily (how
//! many roofs, eaves or clipped, the pillars rising above them or not) is
//! chosen by drawing every style of that many pillars the layout rules
//! know (NR = 0, NE, NE + 1, 2NE, 2NE + 1, 3NE, 3NE + 1; ridge and pillar
//! type) with the lsys renderer, and keeping the one whose lines lie
//! nearest the drawing's; then αEW from the central passage's proportion
//! (measured on the drawing and on the chosen style drawn), and the
//! Toukung levels NTL by drawing 3 to 7 (each set of candidates drawn on
//! every core, the first best kept in the candidates' order, so the answer
//! does not depend on the threads). The tree's leaves are the chosen
//! model's parts, projected onto the drawing.

use super::pailou::{Pailou, PailouType};
use crate::export::render::{render, PixelFrame, RenderOptions, Style, View};
use crate::infer::{Axis, InferError, Inference, Ink, Node, PailouFront, Region};
use crate::mesh::Scene;
use crate::GrammarOptions;

/// αEW, the grammar's entrance width over pillar height (std:pailou).
const ALPHA_EW: f64 = 10.0 / 12.0;
/// The central pillar height when the drawing has no scale (std:pailou's ω).
const OMEGA: f64 = 9.0;
/// Candidates are drawn this many pixels wide at most, and compared on a
/// grid of this many cells across.
const DRAWN: u32 = 400;
const GRID: usize = 160;
/// The Toukung levels are compared drawn this wide, on a grid this wide.
const FINE_DRAWN: u32 = 800;
const FINE: usize = 400;

/// The Pailou drawn in `ink` (named `path`), whose ground pillars are
/// `front`'s; `regions` are the drawing's closed areas (the page draws
/// them); `scale` metres per pixel, if known; `gap` the line breaks
/// bridged (as `--gap`).
pub(super) fn read_pailou(
    ink: &Ink,
    front: &PailouFront,
    regions: Vec<Region>,
    path: &str,
    scale: Option<f64>,
    gap: usize,
) -> Result<Inference, InferError> {
    let centres: Vec<f64> = front
        .pillars
        .iter()
        .map(|p| (p[0] + p[1]) as f64 / 2.0)
        .collect();
    let np = centres.len();
    let half = np / 2;
    // Entrance i's width, the centre outward (i = 1 the central one).
    let widths: Vec<f64> = (0..half)
        .map(|i| centres[half + i] - centres[half + i - 1])
        .map(|w| w.max(1.0))
        .collect();
    let sides: Vec<f64> = widths
        .windows(2)
        .map(|w| ((w[1] / w[0]) * 1000.0).round() / 1000.0)
        .map(|s| s.clamp(0.1, 2.0))
        .collect();
    let omega = scale.map_or(OMEGA, |s| widths[0] * s / ALPHA_EW);
    let omega = (omega * 1000.0).round() / 1000.0;
    let mut defines = vec![("ω".to_string(), omega.to_string())];
    for (i, s) in sides.iter().enumerate() {
        defines.push((format!("side[{}]", i + 1), s.to_string()));
    }
    let target = grid_of_ink(ink, GRID);
    let ne = np - 1;
    let candidates: Vec<(String, PailouType, Pailou)> =
        [0, ne, ne + 1, 2 * ne, 2 * ne + 1, 3 * ne, 3 * ne + 1]
            .into_iter()
            .flat_map(|nr| [PailouType::Ridge, PailouType::Pillar].map(|kind| (nr, kind)))
            .filter_map(|(nr, kind)| {
                let style = format!("{np}-{ne}-{nr}");
                let p = Pailou::style(&style, kind).ok()?;
                Some((style, kind, p))
            })
            .collect();
    let scored = in_parallel(candidates, |(style, kind, p)| {
        let scene = build(&p, &defines)?;
        let score = similarity(&target, &grid_of_scene(scene.mesh(), ink, DRAWN, &target));
        Some((score, style, kind, p, scene))
    });
    // The first best in the candidates' order, whatever order they finished in.
    let mut best: Option<(f64, String, PailouType, Pailou, crate::Scene)> = None;
    for c in scored.into_iter().flatten() {
        if best.as_ref().map_or(true, |b| c.0 > b.0) {
            best = Some(c);
        }
    }
    let (score, style, kind, p, default_scene) = best.ok_or_else(|| InferError::NotPailou {
        path: path.to_string(),
        reason: format!("no style of {np} pillars builds"),
    })?;
    // αEW: the central passage's height over its width is 1/αEW times a
    // constant of the style (every length of a ground entrance is a ratio
    // of its pillar height), so the chosen style drawn with the default
    // αEW, measured the same way, gives it.
    let in_drawing = passage_ratio(front);
    let drawn = full_size(default_scene.mesh(), ink);
    let in_drawn = crate::infer::pailou_front(&drawn, &crate::infer::paper(&drawn, gap).outside)
        .and_then(|f| passage_ratio(&f));
    let alpha_ew = match (in_drawing, in_drawn) {
        (Some(m), Some(d)) if m > 0.0 => {
            ((ALPHA_EW * d / m).clamp(0.3, 3.0) * 1000.0).round() / 1000.0
        }
        _ => ALPHA_EW,
    };
    defines.push(("αEW".to_string(), alpha_ew.to_string()));
    // The Toukung levels: each level raises every row of Toukungs and
    // the roofs on it by a tenth of a Toukung unit, and a side Toukung's
    // reach (where a row ends) with it; a finer grid tells them apart.
    let fine = grid_of_ink(ink, FINE);
    let tried = in_parallel(vec![3.0, 4.0, 5.0, 6.0, 7.0], |ntl| {
        let mut with = defines.clone();
        with.push(("NTL".to_string(), ntl.to_string()));
        let scene = build(&p, &with)?;
        let score = similarity(&fine, &grid_of_scene(scene.mesh(), ink, FINE_DRAWN, &fine));
        Some((score, ntl, scene))
    });
    let mut levels: Option<(f64, f64, crate::Scene)> = None;
    for l in tried.into_iter().flatten() {
        if levels.as_ref().map_or(true, |b| l.0 > b.0) {
            levels = Some(l);
        }
    }
    let (ntl, scene) = match levels {
        Some((_, ntl, scene)) => (ntl, scene),
        None => (5.0, default_scene),
    };
    defines.push(("NTL".to_string(), ntl.to_string()));
    let name = std::path::Path::new(path)
        .file_name()
        .map_or(path.to_string(), |n| n.to_string_lossy().into_owned());
    let kind_name = kind.name();
    let summary = format!(
        "a Pailou front: style {style}, {kind_name} type, {ntl} Toukung levels (its drawing matches the drawing's lines to {score:.2}); entrance widths {}",
        widths.iter().map(|w| format!("{w:.0}")).collect::<Vec<_>>().join(", ")
    );
    let measured = Measured {
        omega,
        omega_from_scale: scale.is_some(),
        alpha_ew,
        levels: ntl,
        sides,
    };
    let grammar = grammar_text(&p, &name, &summary, &measured);
    let tree = tree_of(ink, front, scene.mesh());
    Ok(Inference {
        width: ink.width,
        height: ink.height,
        regions,
        tree,
        unlabelled: Vec::new(),
        missed: Vec::new(),
        grammar,
        summary: Some(summary),
        build_defines: ["TM.NTL", "TS.NTL"]
            .map(|n| (n.to_string(), ntl.to_string()))
            .to_vec(),
    })
}

/// `f` of each item, in the items' order, on as many threads as the
/// machine has cores (each with the compiler's deep stack): the
/// candidates are independent builds and drawings.
fn in_parallel<T: Send, R: Send>(items: Vec<T>, f: impl Fn(T) -> R + Sync) -> Vec<R> {
    let threads = crate::derive::threads().min(items.len());
    if threads < 2 {
        return items.into_iter().map(f).collect();
    }
    let n = items.len();
    let todo: Vec<std::sync::Mutex<Option<T>>> = items
        .into_iter()
        .map(|t| std::sync::Mutex::new(Some(t)))
        .collect();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let (todo, next, f) = (&todo, &next, &f);
    let mut done: Vec<(usize, R)> = std::thread::scope(|s| {
        let workers: Vec<_> = (0..threads)
            .filter_map(|w| {
                std::thread::Builder::new()
                    .name(format!("lsys infer {w}"))
                    .stack_size(super::WORKER_STACK)
                    .spawn_scoped(s, move || {
                        let mut mine = Vec::new();
                        loop {
                            let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                            let Some(slot) = todo.get(k) else { break };
                            let item = slot.lock().ok().and_then(|mut t| t.take());
                            if let Some(item) = item {
                                mine.push((k, f(item)));
                            }
                        }
                        mine
                    })
                    .ok()
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
            .collect()
    });
    // A worker that could not start leaves its items here.
    for (k, slot) in todo.iter().enumerate() {
        if let Some(item) = slot.lock().ok().and_then(|mut t| t.take()) {
            done.push((k, f(item)));
        }
    }
    done.sort_by_key(|d| d.0);
    debug_assert_eq!(done.len(), n);
    done.into_iter().map(|d| d.1).collect()
}

/// The scene of `p` with `defines`, components as boxes and bare roofs
/// (the lines that decide between styles are the big ones).
fn build(p: &Pailou, defines: &[(String, String)]) -> Option<crate::Scene> {
    let job = p.job(GrammarOptions::default().defines_from(defines).detail(0));
    super::run(&job, &mut |_| {}).ok().map(|d| d.scene)
}

/// Ink cells of a grid over the ink's box, one flag per cell.
struct Grid {
    w: usize,
    h: usize,
    on: Vec<bool>,
}

fn ink_box(w: usize, h: usize, at: impl Fn(usize, usize) -> bool) -> Option<[usize; 4]> {
    let mut b = [usize::MAX, usize::MAX, 0, 0];
    for y in 0..h {
        for x in 0..w {
            if at(x, y) {
                b = [b[0].min(x), b[1].min(y), b[2].max(x + 1), b[3].max(y + 1)];
            }
        }
    }
    (b[0] < b[2]).then_some(b)
}

fn grid(w: usize, h: usize, at: impl Fn(usize, usize) -> bool, cols: usize, rows: usize) -> Grid {
    let mut g = Grid {
        w: cols,
        h: rows,
        on: vec![false; cols * rows],
    };
    let Some(b) = ink_box(w, h, &at) else {
        return g;
    };
    let (bw, bh) = ((b[2] - b[0]) as f64, (b[3] - b[1]) as f64);
    for y in b[1]..b[3] {
        for x in b[0]..b[2] {
            if at(x, y) {
                let gx = (((x - b[0]) as f64 / bw) * cols as f64) as usize;
                let gy = (((y - b[1]) as f64 / bh) * rows as f64) as usize;
                g.on[gy.min(rows - 1) * cols + gx.min(cols - 1)] = true;
            }
        }
    }
    g
}

/// Rows of a grid `cols` wide: the drawing's ink box's proportions.
fn rows_for(ink: &Ink, cols: usize) -> usize {
    let b = ink_box(ink.width, ink.height, |x, y| ink.at(x, y)).unwrap_or([0, 0, 1, 1]);
    let ratio = (b[3] - b[1]) as f64 / (b[2] - b[0]).max(1) as f64;
    ((cols as f64 * ratio).round() as usize).clamp(8, 4 * cols)
}

fn grid_of_ink(ink: &Ink, cols: usize) -> Grid {
    grid(
        ink.width,
        ink.height,
        |x, y| ink.at(x, y),
        cols,
        rows_for(ink, cols),
    )
}

/// `scene` drawn as the drawing would be (front, lines), `drawn` pixels
/// wide at most, on a grid of `like`'s size (the drawing's).
fn grid_of_scene(scene: &Scene, ink: &Ink, drawn: u32, like: &Grid) -> Grid {
    let k = (f64::from(drawn) / ink.width as f64).min(1.0);
    let opts = RenderOptions {
        width: ((ink.width as f64 * k) as u32).max(16),
        height: ((ink.height as f64 * k) as u32).max(16),
        ..front_lines(ink, 1)
    };
    let img = render(scene, &opts);
    let (w, h) = (img.width as usize, img.height as usize);
    let dark = |x: usize, y: usize| img.rgb[(y * w + x) * 3] < 128;
    grid(w, h, dark, like.w, like.h)
}

/// How near two grids' lines lie: the share of each one's cells with a
/// cell of the other within one cell, the harmonic mean of the two.
fn similarity(a: &Grid, b: &Grid) -> f64 {
    let near = |g: &Grid, x: usize, y: usize| {
        (y.saturating_sub(1)..=(y + 1).min(g.h - 1))
            .any(|yy| (x.saturating_sub(1)..=(x + 1).min(g.w - 1)).any(|xx| g.on[yy * g.w + xx]))
    };
    let covered = |p: &Grid, q: &Grid| {
        let (mut n, mut hit) = (0usize, 0usize);
        for y in 0..p.h {
            for x in 0..p.w {
                if p.on[y * p.w + x] {
                    n += 1;
                    hit += usize::from(near(q, x, y));
                }
            }
        }
        if n == 0 {
            0.0
        } else {
            hit as f64 / n as f64
        }
    };
    let (p, r) = (covered(a, b), covered(b, a));
    if p + r == 0.0 {
        0.0
    } else {
        2.0 * p * r / (p + r)
    }
}

/// A front elevation in lines at the drawing's size.
fn front_lines(ink: &Ink, supersample: u32) -> RenderOptions {
    RenderOptions {
        view: View::Front,
        style: Style::Lines,
        width: ink.width as u32,
        height: ink.height as u32,
        supersample,
    }
}

/// `scene` drawn as the drawing is (front, lines, its size), as ink.
fn full_size(scene: &Scene, ink: &Ink) -> Ink {
    let img = render(scene, &front_lines(ink, 2));
    Ink {
        width: img.width as usize,
        height: img.height as usize,
        ink: img.rgb.chunks(3).map(|p| p[0] < 128).collect(),
    }
}

/// The central passage's height (the ink's bottom to the first line above
/// the ground between the two middle pillars) over its width (pillar
/// centre to centre).
fn passage_ratio(front: &PailouFront) -> Option<f64> {
    let half = front.pillars.len() / 2;
    let (l, r) = (front.pillars.get(half - 1)?, front.pillars.get(half)?);
    let width = (r[0] + r[1]) as f64 / 2.0 - (l[0] + l[1]) as f64 / 2.0;
    let [_, top, _, end] = *front.passages.get(half - 1)?;
    (width > 0.0).then(|| (end - 1 - top) as f64 / width)
}

/// What was measured on the drawing, written into the grammar.
struct Measured {
    omega: f64,
    omega_from_scale: bool,
    alpha_ew: f64,
    levels: f64,
    sides: Vec<f64>,
}

/// The grammar `lsys pailou --emit-lsys` writes for `p`, with what was
/// measured written into its defines and a heading saying where it came
/// from.
fn grammar_text(p: &Pailou, name: &str, summary: &str, m: &Measured) -> String {
    let mut side_table: Vec<String> = m.sides.iter().map(|s| s.to_string()).collect();
    side_table.resize(6, "αSide".to_string());
    let mut out = format!(
        "// Inferred by `lsys infer` from {name}: {summary}.\n// The proportions measured are written into the defines below. The Toukungs\n// have {n} levels: build with `lsys build FILE -D TM.NTL={n} -D TS.NTL={n}` (the\n// Toukung grammars' own define; `lsys pailou` passes NTL on by itself).\n",
        n = m.levels
    );
    for line in p.grammar_text().lines() {
        if line.starts_with("#define ω ") {
            let why = if m.omega_from_scale {
                "measured: the central entrance's width (--scale) over αEW"
            } else {
                "the drawing has no scale (lsys infer --scale M/PX sets one): std:pailou's"
            };
            out.push_str(&format!(
                "#define ω {}                     // {why}\n",
                m.omega
            ));
        } else if line.starts_with("#define αPW ") {
            out.push_str(&line.replace("αEW 10/12", &format!("αEW {}", m.alpha_ew)));
            out.push_str("   // αEW measured: the central passage's height over its width\n");
        } else if line.starts_with("#define NTL ") {
            out.push_str(&line.replace("NTL 5", &format!("NTL {}", m.levels)));
            out.push_str("   // NTL chosen by drawing 3 to 7 levels\n");
        } else if line.starts_with("#define side[1..6]") {
            out.push_str(&format!(
                "#define side[1..6] {{ {} }}   // measured: each entrance's width over the inner one's\n",
                side_table.join(", ")
            ));
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    out
}

/// The vocabulary's label of a std:pailou component.
fn label_of(component: &str) -> &'static str {
    match component {
        "MP" => "column",
        "ML" | "MLO" | "MLS" => "lintel",
        "MFB" | "MIB" | "MBP" => "wall",
        "TM" | "TS" => "bracket",
        "RE" | "RC" => "roof",
        "MRO" | "MSA" | "MPC" | "MCH" => "ornament",
        _ => "other",
    }
}

/// The tree: the drawing's box cut along x at the ground pillars' sides
/// (pillars and the entrances between them), each slice the parts whose
/// middle is in it, top to bottom: the chosen model's parts projected
/// onto the drawing (its box mapped onto the drawing's ink box), and each
/// passage between two ground pillars a bay.
fn tree_of(ink: &Ink, front: &PailouFront, scene: &Scene) -> Node {
    let b = ink_box(ink.width, ink.height, |x, y| ink.at(x, y)).unwrap_or([0, 0, 1, 1]);
    let bbox = [b[0] as i32, b[1] as i32, b[2] as i32, b[3] as i32];
    let leaves: Vec<(&'static str, [f64; 4])> = PixelFrame::of(scene, &front_lines(ink, 1))
        .map(|frame| frame.instance_boxes(scene))
        .unwrap_or_default()
        .into_iter()
        .map(|(name, b)| (label_of(name), b))
        .collect();
    // The model's box as projected, mapped onto the drawing's ink box.
    let union = leaves
        .iter()
        .fold([f64::MAX, f64::MAX, f64::MIN, f64::MIN], |u, (_, b)| {
            [
                u[0].min(b[0]),
                u[1].min(b[1]),
                u[2].max(b[2]),
                u[3].max(b[3]),
            ]
        });
    let map = |v: f64, from: (f64, f64), to: (i32, i32)| -> i32 {
        let t = if from.1 > from.0 {
            (v - from.0) / (from.1 - from.0)
        } else {
            0.0
        };
        (f64::from(to.0) + t * f64::from(to.1 - to.0)).round() as i32
    };
    let mut parts: Vec<(&'static str, [i32; 4])> = leaves
        .iter()
        .map(|(l, b)| {
            let x = |v| map(v, (union[0], union[2]), (bbox[0], bbox[2]));
            let y = |v| map(v, (union[1], union[3]), (bbox[1], bbox[3]));
            (*l, [x(b[0]), y(b[1]), x(b[2]), y(b[3])])
        })
        .collect();
    for p in &front.passages {
        parts.push(("bay", p.map(|v| v as i32)));
    }
    // Slices along x.
    let mut cuts = vec![bbox[0]];
    for p in &front.pillars {
        cuts.extend([p[0] as i32, p[1] as i32]);
    }
    cuts.push(bbox[2]);
    cuts.dedup();
    let mut children = Vec::new();
    for s in cuts.windows(2) {
        let (x0, x1) = (s[0], s[1]);
        let last = x1 == bbox[2];
        let mut inside: Vec<Node> = parts
            .iter()
            .filter(|(_, b)| {
                let mid = (b[0] + b[2]) / 2;
                mid >= x0 && (mid < x1 || (last && mid <= x1))
            })
            .map(|&(label, b)| Node::leaf(label, b))
            .collect();
        if inside.is_empty() {
            continue;
        }
        inside.sort_by_key(|n| (n.bbox[1], n.bbox[0]));
        let mut slice = Node::leaf("other", [x0, bbox[1], x1, bbox[3]]);
        slice.split = Some(Axis::Y);
        slice.children = inside;
        children.push(slice);
    }
    let mut root = Node::leaf("other", bbox);
    root.split = Some(Axis::X);
    root.children = children;
    root
}
