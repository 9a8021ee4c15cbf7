//! Rules: a labelled shape tree -> a `.lsys` shape grammar in the notation
//! of `docs/shapes.md` that rebuilds the hall in 3D, written as a person
//! would write it: the measured sizes as `#define`s in metres, the bays as
//! a symmetric repeat split, bracket sets, rafters and tiles as repeat
//! splits, so that `-D W=` a larger width gives more bays and bracket sets.
//!
//! Depth is not in an elevation; it follows seed 003's Section 7.1: the
//! rafters' horizontal step (bujia) is solved from the roof's height and the
//! rises of the purlins (jujia 0.5, 0.7 and 0.9 of the step, for a roof of
//! seven purlins), the roof is six steps deep, the levels are concentric
//! (the room is as much shallower than the roof as it is narrower), and
//! the corridor is one step deep. The roof's slope is those purlins' steps
//! (`@Roof`), hipped when the drawing's roof ends slope down (a hip line
//! at each end, not the upright end of a gable).

use std::fmt::Write;

use super::drawing::Ink;
use super::tree::Node;

/// What fills a bay under its lintel.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Fill {
    Wall,
    /// Width as a fraction of the bay, sill and head heights (metres).
    Window {
        frac: f64,
        sill: f64,
        head: f64,
    },
    /// Width as a fraction of the bay, head height above it (metres).
    Door {
        frac: f64,
        head: f64,
    },
}

/// One bay: its width centre to centre of its columns (metres) and fill.
#[derive(Clone, Copy, Debug)]
struct Bay {
    width: f64,
    fill: Fill,
}

/// A row of repeated elements (bracket sets, rafters).
#[derive(Clone, Copy, Debug)]
struct Row {
    height: f64,
    /// Elements on the front face.
    count: usize,
    /// Width of one element (metres).
    element: f64,
    /// The row goes round the corners: at each end an element unlike the
    /// others (the side face's first, seen end-on) stands beyond the front.
    corners: bool,
}

/// The hall as measured from the drawing, in metres.
#[derive(Clone, Debug)]
pub struct Measured {
    /// Metres per drawing pixel.
    pub scale: f64,
    width: f64,
    room: f64,
    column: f64,
    lintel: f64,
    bays: Vec<Bay>,
    platform: Option<(f64, f64)>,
    stairs: Option<(f64, usize)>,
    brackets: Option<Row>,
    rafters: Option<Row>,
    roof: Option<(f64, f64)>,
    /// The roof's ends slope down: a hip roof.
    hip: bool,
    ridge: Option<f64>,
    /// Ornaments on the ridge's ends: their height.
    ornament: Option<f64>,
}

/// Column height assumed when no scale is given: the seed's halls stand
/// on columns about 4.2 m high.
pub const COLUMN_METRES: f64 = 4.2;

fn find<'a>(n: &'a Node, label: &str, out: &mut Vec<&'a Node>) {
    if n.label == label {
        out.push(n);
    }
    for c in &n.children {
        find(c, label, out);
    }
}

fn all<'a>(n: &'a Node, label: &str) -> Vec<&'a Node> {
    let mut out = Vec::new();
    find(n, label, &mut out);
    out
}

fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// A hip roof seen from the front: near each end of the roof's box the
/// highest ink is in the lower half (the hip line and the end slope's
/// short rows of tiles), where a gable's upright end reaches the top.
fn hipped(roof: &Node, ink: &Ink) -> bool {
    let [x0, y0, x1, y1] = roof.bbox.map(|v| v.max(0) as usize);
    let (x1, y1) = (x1.min(ink.width), y1.min(ink.height));
    if x1 <= x0 + 20 || y1 <= y0 + 4 {
        return false;
    }
    let strip = ((x1 - x0) / 40).max(2);
    let top = |xs: std::ops::Range<usize>| {
        (y0..y1)
            .find(|&y| xs.clone().any(|x| ink.at(x, y)))
            .unwrap_or(y1)
    };
    let half = y0 + (y1 - y0) / 2;
    top(x0..x0 + strip) > half && top(x1 - strip..x1) > half
}

/// Measures the labelled tree. `scale` is metres per pixel; `None` takes
/// the columns as [`COLUMN_METRES`] high.
pub fn measure(root: &Node, scale: Option<f64>, ink: &Ink) -> Measured {
    let mut columns = all(root, "column");
    columns.sort_by_key(|c| c.bbox[0]);
    let bays = all(root, "bay");
    // The body: the band holding the bays and columns.
    let body = root
        .children
        .iter()
        .find(|b| {
            b.children
                .iter()
                .any(|c| c.label == "bay" || c.label == "column")
        })
        .or_else(|| root.children.iter().find(|b| b.label == "bay"))
        .unwrap_or(root);
    let room_px = body.h().max(1) as f64;
    let s = scale.unwrap_or(COLUMN_METRES / room_px);
    let col_px = median(columns.iter().map(|c| c.w() as f64).collect());
    let centre = |n: &Node| (n.bbox[0] + n.bbox[2]) as f64 / 2.0;
    // Bay edges: column centres, or the body's ends without columns there.
    let mut edges: Vec<f64> = columns.iter().map(|c| centre(c)).collect();
    let (bx0, bx1) = (body.bbox[0] as f64, body.bbox[2] as f64);
    if far(edges.first(), bx0, col_px) {
        edges.insert(0, bx0);
    }
    if far(edges.last(), bx1, col_px) {
        edges.push(bx1);
    }
    let mut measured_bays = Vec::new();
    for w in edges.windows(2) {
        let (a, b) = (w[0], w[1]);
        let Some(bay) = bays.iter().find(|n| (a..b).contains(&centre(n))) else {
            continue;
        };
        measured_bays.push(Bay {
            width: (b - a) * s,
            fill: fill(bay, col_px, s),
        });
    }
    let lintel = median(all(root, "lintel").iter().map(|n| n.h() as f64).collect()) * s;
    let width = if measured_bays.is_empty() {
        body.w() as f64 * s
    } else {
        measured_bays.iter().map(|b| b.width).sum()
    };
    let band = |label: &str| root.children.iter().find(|b| b.label == label);
    let platform = root
        .children
        .iter()
        .filter(|b| b.label == "platform")
        .map(|b| {
            (
                b.h() as f64 * s,
                ((b.w() as f64 * s) - width).max(0.0) / 2.0,
            )
        })
        .reduce(|a, b| (a.0 + b.0, a.1.max(b.1)));
    let stairs = all(root, "stairs")
        .first()
        .map(|n| (n.w() as f64 * s, n.regions.len().clamp(1, 9)));
    let row = |label: &str| -> Option<Row> {
        // The recogniser may have nested the row in its band (margins
        // around a narrower layer, rows re-cut into columns).
        let (band, mut items) = root
            .children
            .iter()
            .map(|b| (b, all(b, label)))
            .find(|(_, items)| !items.is_empty())?;
        items.sort_by_key(|n| n.bbox[0]);
        // Rafters read by their pitch go on under the eaves past the
        // front (pitch/rafters.rs): the front's are those between the end bays'
        // edges, and a row that goes on past both ends goes round.
        let (lo, hi) = match (edges.first(), edges.last()) {
            (Some(&a), Some(&b)) if label == "rafter" => (a - 1.0, b + 1.0),
            _ => (f64::MIN, f64::MAX),
        };
        let past_both = items.first().is_some_and(|n| centre(n) < lo)
            && items.last().is_some_and(|n| centre(n) > hi);
        // Else a side face's rafters or bracket sets seen end-on: the first
        // and the last element, both more than a quarter narrower or wider
        // than the others, or both closer to their neighbour than three
        // quarters of the pitch (an end-on set stands at the corner, half
        // a pitch from the front's first: the widths can be alike).
        let corners = past_both
            || items.len() >= 4 && {
                let k = items.len();
                let m = median(items[1..k - 1].iter().map(|n| n.w() as f64).collect());
                let unlike = |n: &Node| (n.w() as f64 - m).abs() > 0.25 * m;
                let gap = |i: usize| centre(items[i + 1]) - centre(items[i]);
                let pitch = median((1..k - 2).map(gap).collect());
                let close = |i: usize| gap(i) < 0.75 * pitch;
                (unlike(items[0]) && unlike(items[k - 1])) || (k >= 5 && close(0) && close(k - 2))
            };
        if past_both {
            items.retain(|n| (lo..=hi).contains(&centre(n)));
        } else if corners {
            items = items[1..items.len() - 1].to_vec();
        }
        Some(Row {
            height: band.h() as f64 * s,
            count: items.len(),
            element: median(items.iter().map(|n| n.w() as f64).collect()) * s,
            corners,
        })
    };
    let roof = band("roof").map(|r| {
        (
            r.h() as f64 * s,
            ((r.w() as f64 * s) - width).max(0.0) / 2.0,
        )
    });
    Measured {
        scale: s,
        width,
        room: room_px * s,
        column: col_px * s,
        lintel,
        bays: measured_bays,
        platform,
        stairs,
        brackets: row("bracket"),
        rafters: row("rafter"),
        roof,
        hip: band("roof").is_some_and(|r| hipped(r, ink)),
        ridge: band("ridge").map(|r| r.h() as f64 * s),
        ornament: band("ornament").map(|r| r.h() as f64 * s),
    }
}

/// No column at `edge`, or it is more than `d` pixels from `x`.
fn far(edge: Option<&f64>, x: f64, d: f64) -> bool {
    edge.map_or(true, |&c| (c - x).abs() > d.max(1.0))
}

/// What fills a bay, from its door or window and the box under its lintel.
/// Widths are fractions of the bay's pitch (the drawn bay between column
/// faces plus one column, `col_px` wide), as the rebuilt facade's bays run
/// from column centre to column centre.
fn fill(bay: &Node, col_px: f64, s: f64) -> Fill {
    let lintel = bay.children.iter().find(|c| c.label == "lintel");
    let below = [
        bay.bbox[0],
        lintel.map_or(bay.bbox[1], |l| l.bbox[3]),
        bay.bbox[2],
        bay.bbox[3],
    ];
    let (bw, bh) = (
        (below[2] - below[0]).max(1) as f64 + col_px,
        (below[3] - below[1]).max(1) as f64,
    );
    let door = all(bay, "door");
    let window = all(bay, "window");
    if let Some(d) = door.first() {
        return Fill::Door {
            frac: (d.w() as f64 / bw).clamp(0.05, 1.0),
            head: ((d.bbox[1] - below[1]).max(0) as f64 * s).min(bh * s * 0.5),
        };
    }
    if let Some(w) = window.first() {
        return Fill::Window {
            frac: (w.w() as f64 / bw).clamp(0.05, 1.0),
            sill: (below[3] - w.bbox[3]).max(0) as f64 * s,
            head: (w.bbox[1] - below[1]).max(0) as f64 * s,
        };
    }
    Fill::Wall
}

/// The jujia of a seven-purlin roof: each purlin's rise over one step.
const JUJIA: [f64; 3] = [0.5, 0.7, 0.9];

fn num(x: f64) -> String {
    let r = (x * 1000.0).round() / 1000.0;
    let t = format!("{r:.3}");
    let t = t.trim_end_matches('0');
    let t = t
        .strip_suffix('.')
        .map_or(t.to_string(), |t| format!("{t}.0"));
    if t == "-0.0" {
        "0.0".to_string()
    } else {
        t
    }
}

impl Measured {
    /// The grammar, headed by a comment naming `source`.
    pub fn grammar(&self, source: &str, unlabelled: usize) -> String {
        let mut g = String::new();
        let bays = &self.bays;
        let n = bays.len();
        let mean = |v: &[f64]| {
            if v.is_empty() {
                0.0
            } else {
                v.iter().sum::<f64>() / v.len() as f64
            }
        };
        let (end, bay, centre) = match n {
            0 => (self.width, self.width, self.width),
            1 => (bays[0].width, bays[0].width, bays[0].width),
            _ => {
                let end = (bays[0].width + bays[n - 1].width) / 2.0;
                let mid = bays[n / 2].width;
                let others: Vec<f64> = bays[1..n - 1]
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| n % 2 == 0 || k + 1 != n / 2)
                    .map(|(_, b)| b.width)
                    .collect();
                let measured = if others.is_empty() {
                    (end + mid) / 2.0
                } else {
                    mean(&others)
                };
                // The drawing shows n bays of a side stretched to fill; any
                // nominal size between inner/(2n+2) and inner/(2n) gives n
                // again. Take the middle, inner/(2n+1), so that a wider
                // scope gains bays when a generator's would.
                let side = others.len().div_ceil(2).max(1) as f64;
                let inner = 2.0 * side * measured;
                let bay = if others.is_empty() {
                    measured
                } else {
                    inner / (2.0 * side + 1.0)
                };
                let centre = if n % 2 == 1 { mid } else { bay };
                (end, bay, centre)
            }
        };
        let kinds = [
            ("End", bays.first().map_or(Fill::Wall, |b| b.fill)),
            (
                "",
                bays.get(1)
                    .filter(|_| n > 3)
                    .or(bays.get(n / 2))
                    .map_or(Fill::Wall, |b| b.fill),
            ),
            ("Centre", bays.get(n / 2).map_or(Fill::Wall, |b| b.fill)),
        ];
        let plat = self.platform.unwrap_or((0.0, 0.0));
        let (roof_h, ov) = self.roof.unwrap_or((self.room * 0.6, 0.0));
        let brk = self.brackets;
        let raf = self.rafters;
        let ridge = self.ridge.unwrap_or(0.0);
        // A repeat split of `count` pieces over the width: the piece in
        // the middle of the sizes that give `count` again (as for the
        // bays); an element at most 0.8 of it.
        let pitch = |r: Option<Row>, default: f64| {
            r.map_or(default, |r| self.width / (r.count.max(1) as f64 + 0.5))
        };
        let element = |r: Option<Row>, default: f64| {
            r.map_or(default, |r| r.element.min(0.8 * pitch(Some(r), default)))
        };
        let lintel = if self.lintel > 0.0 {
            self.lintel
        } else {
            self.room * 0.12
        };
        let col = if self.column > 0.0 {
            self.column
        } else {
            self.room * 0.1
        };

        let _ = writeln!(g, "/* A hall inferred by `lsys infer` from {source}.");
        let _ = writeln!(
            g,
            "   {} bays ({}), {} columns; sizes in metres at {} m a pixel.",
            n,
            bays.iter()
                .map(|b| match b.fill {
                    Fill::Wall => "wall",
                    Fill::Window { .. } => "window",
                    Fill::Door { .. } => "door",
                })
                .collect::<Vec<_>>()
                .join(", "),
            if self.column > 0.0 { n + 1 } else { 0 },
            num(self.scale)
        );
        if unlabelled > 0 {
            let _ = writeln!(
                g,
                "   {unlabelled} drawn region(s) could not be labelled and are not rebuilt."
            );
        }
        let _ = writeln!(
            g,
            "   Build it wider with -D W=...: the bays, bracket sets, rafters and tiles"
        );
        let _ = writeln!(
            g,
            "   repeat as the width affords. Depth follows seed 003's Sec 7.1. */"
        );
        let _ = writeln!(g);
        let mut defs: Vec<(&str, String, &str)> = vec![
            (
                "W",
                num(self.width),
                "facade width, centre to centre of the end columns",
            ),
            ("PLAT", num(plat.0), "platform height"),
            (
                "POV",
                num(plat.1),
                "platform beyond the facade on each side",
            ),
            ("ROOM", num(self.room), "column height"),
            (
                "BRK",
                num(brk.map_or(0.0, |r| r.height)),
                "bracket-set layer",
            ),
            ("RAF", num(raf.map_or(0.0, |r| r.height)), "rafter layer"),
            ("ROOF", num(roof_h), "roof height"),
            ("RIDGE", num(ridge), "ridge height"),
            ("OV", num(ov), "eaves overhang beyond the facade"),
            (
                "HIP",
                u8::from(self.hip).to_string(),
                "1: hip roof (its ends slope down); 0: gable",
            ),
            ("COL", num(col), "column diameter"),
            ("LINTEL", num(lintel), "lintel height"),
            ("END", num(end), "the two end bays"),
            ("BAY", num(bay), "other bays: about this wide"),
            ("CENTRE", num(centre), "the centre bay"),
            (
                "BRK_PITCH",
                num(pitch(brk, 1.0)),
                "one bracket set per this much width",
            ),
            ("BRK_W", num(element(brk, 0.5)), "bracket-set width"),
            (
                "RAF_PITCH",
                num(pitch(raf, 0.4)),
                "one rafter per this much width",
            ),
            ("RAF_W", num(element(raf, 0.15)), "rafter width"),
            (
                "STAIRS",
                num(self.stairs.map_or(0.0, |s| s.0)),
                "stairs width",
            ),
        ];
        if let Some(h) = self.ornament {
            defs.push(("ORN", num(h), "ornaments on the ridge's ends: their height"));
        }
        for (name, value, why) in &defs {
            let _ = writeln!(g, "#define {name} {value} // {why}");
        }
        let _ = writeln!(g, "#define PURLINS 7 // the roof's purlins");
        let _ = writeln!(
            g,
            "#define BUJIA (ROOF / {}) // one rafter step, from the roof's rise",
            num(JUJIA.iter().sum())
        );
        let _ = writeln!(g, "#define ROOF_D ((PURLINS - 1) * BUJIA) // roof depth");
        let _ = writeln!(
            g,
            "#define DEPTH max(ROOF_D - 2 * OV, 3 * BUJIA) // concentric levels"
        );
        let _ = writeln!(g, "#define CORR BUJIA // corridor depth");
        for (k, (prefix, f)) in kinds.iter().enumerate() {
            let p = ["E", "B", "C"][k];
            match f {
                Fill::Window { frac, sill, head } => {
                    let _ = writeln!(
                        g,
                        "#define {p}_WIN {} // {}bay window: width over the bay's",
                        num(*frac),
                        prefix.to_lowercase()
                    );
                    let _ = writeln!(g, "#define {p}_SILL {}", num(sill.max(0.05)));
                    let _ = writeln!(g, "#define {p}_HEAD {}", num(head.max(0.05)));
                }
                Fill::Door { frac, head } => {
                    let _ = writeln!(
                        g,
                        "#define {p}_DOOR {} // {}bay door: width over the bay's",
                        num(*frac),
                        prefix.to_lowercase()
                    );
                    let _ = writeln!(g, "#define {p}_HEAD {}", num(head.max(0.05)));
                }
                Fill::Wall => {}
            }
        }
        g.push_str(COLOURS);
        let _ = writeln!(g);
        let _ = writeln!(g, "derivation length: 12");
        let _ = writeln!(
            g,
            "module Hall, Platform, Room, Inner, Corridor, Pier, Column, Brackets, BrkFace"
        );
        let _ = writeln!(
            g,
            "module BrkSet, Rafters, RafFace, Rafter, Roof, Ridge, {}Facade, EndBay, Bay",
            if self.ornament.is_some() {
                "RidgeEnds, Wen, "
            } else {
                ""
            }
        );
        let _ = writeln!(g, "module CentreBay, EndFill, BayFill, CentreFill, Window, Lattice, Door, Leaf, Wall, Side, Stairs");
        let _ = writeln!(g);
        let _ = writeln!(
            g,
            "Axiom: @Scope(W, PLAT + ROOM + BRK + RAF + ROOF + RIDGE, DEPTH) Hall"
        );
        let _ = writeln!(g);
        // Layers that were not drawn have zero height: leave them out of
        // the split (a zero piece is legal but says nothing).
        let layers: Vec<(&str, &str, bool)> = vec![
            ("PLAT", "Platform", self.platform.is_some()),
            ("ROOM", "Room", true),
            ("BRK", "Brackets", brk.is_some()),
            ("RAF", "Rafters", raf.is_some()),
            ("ROOF", "Roof", true),
            ("RIDGE", "Ridge", self.ridge.is_some()),
        ];
        let used: Vec<&(&str, &str, bool)> = layers.iter().filter(|l| l.2).collect();
        let _ = writeln!(
            g,
            "Hall --> @SY({})\n         {}",
            used.iter().map(|l| l.0).collect::<Vec<_>>().join(", "),
            used.iter()
                .map(|l| format!("[{}]", l.1))
                .collect::<Vec<_>>()
                .join(" ")
        );
        if self.platform.is_some() {
            g.push_str(
                "Platform --> [;(16) @Tr(-POV, 0, -POV) @Grow(2 * POV, 0, 2 * POV) @Block]\n",
            );
            if let Some((_, steps)) = self.stairs {
                g.push_str("             @Tr(0, 0, DEPTH + POV) @Scope(W, PLAT, 1.2)\n");
                g.push_str("             @SX(flo(1), STAIRS, flo(1)) [] [Stairs] []\n");
                let pieces = vec!["flo(1)"; steps].join(", ");
                // Each step set back from the one below.
                let blocks: Vec<String> = (0..steps)
                    .map(|k| match k {
                        0 => "[@Block]".to_string(),
                        _ => format!(
                            "[@Grow(0, 0, -{}) @Block]",
                            num(k as f64 * 1.2 / steps as f64)
                        ),
                    })
                    .collect();
                let _ = writeln!(g, "Stairs --> ;(16) @SY({pieces}) {}", blocks.join(" "));
            }
        }
        let jujia: Vec<String> = JUJIA.iter().map(|&j| num(j)).collect();
        g.push_str(&FIXED_RULES.replace("JUJIA", &jujia.join(", ")));
        // A row seen going round the corners is on all four faces.
        let faces = |r: Row, face: &str| {
            if r.corners {
                format!("@Comp [{face}] [{face}] [{face}] [{face}] [] []")
            } else {
                format!("@Comp [{face}]")
            }
        };
        if let Some(r) = brk {
            g.push_str(&BRACKETS.replace("@Comp [BrkFace]", &faces(r, "BrkFace")));
        }
        if let Some(r) = raf {
            g.push_str(&RAFTERS.replace("@Comp [RafFace]", &faces(r, "RafFace")));
        }
        if self.ridge.is_some() {
            // A hip roof's ridge runs between its hips: shorter than the
            // facade by the depth.
            let ridge = if self.ornament.is_some() {
                "[[;(20) @Block] RidgeEnds]"
            } else {
                "[;(20) @Block]"
            };
            let _ = writeln!(
                g,
                "Ridge --> @Tr(HIP * min(DEPTH, W) / 2 - 0.3, 0, 0) @Grow(0.6 - HIP * min(DEPTH, W), 0, 0)\n          @SZ(flo(1), 0.5, flo(1)) [] {ridge} []"
            );
            if self.ornament.is_some() {
                // The ornaments: the built-in chiwen (its width 1/1.3 of
                // its height), the jaw toward the ridge, the far one
                // turned about the vertical.
                g.push_str("RidgeEnds --> @SX(ORN / 1.3, flo(1), ORN / 1.3) [Wen] [] [@Rot(0, 180, 0) Wen]\nWen --> @Tr(0, RIDGE, 0.1) @Grow(0, ORN - RIDGE, 0) @Ext(0.3) ;(18) ~MRO\n");
            }
        }
        g.push_str("\n// Each bay: the lintel on top, under it what the drawing shows.\n");
        for (k, (prefix, f)) in kinds.iter().enumerate() {
            let p = ["E", "B", "C"][k];
            let name = if prefix.is_empty() {
                "Bay".to_string()
            } else {
                format!("{prefix}Bay")
            };
            let fill = if prefix.is_empty() {
                "BayFill".to_string()
            } else {
                format!("{prefix}Fill")
            };
            let _ = writeln!(
                g,
                "{name} --> @SY(flo(1), LINTEL) [{fill}] [;(17) @Ext(0.35) @Block]"
            );
            let _ = match f {
                Fill::Wall => writeln!(g, "{fill} --> Wall"),
                Fill::Window { .. } => writeln!(
                    g,
                    "{fill} --> @SY({p}_SILL, flo(1), {p}_HEAD) [Wall] [@SX(flo(1), rel({p}_WIN), flo(1)) [Wall] [Window] [Wall]] [Wall]"
                ),
                Fill::Door { .. } => writeln!(
                    g,
                    "{fill} --> @SX(flo(1), rel({p}_DOOR), flo(1)) [Wall] [@SY(flo(1), {p}_HEAD) [Door] [Wall]] [Wall]"
                ),
            };
        }
        g.push_str(WALL);
        // Only what some bay holds: a production that never fires is a
        // warning when the grammar is built.
        if kinds.iter().any(|(_, f)| matches!(f, Fill::Window { .. })) {
            g.push_str(WINDOW);
        }
        if kinds.iter().any(|(_, f)| matches!(f, Fill::Door { .. })) {
            g.push_str(DOOR);
        }
        g
    }
}

const COLOURS: &str = "
colour 16: #8a8478   // stone
colour 17: #9e2a22   // red lacquer
colour 18: #c9a23f   // gilded brackets
colour 19: #5a4632   // dark wood
colour 20: #2f5f5a   // glazed tiles
colour 21: #d8cfc0   // plaster
colour 26: #2f5f5a   // the roof's shell
colour 27: #3f7a72   // its rows of tiles
";

const FIXED_RULES: &str = "Room --> @SZ(flo(1), CORR) [Inner] [Corridor]
Inner --> @Comp [Facade] [Side] [Side] [Side]
Side --> ;(21) @Ext(0.3) @Block
Facade --> @RSX(END, BAY, CENTRE) [EndBay] [Bay] [CentreBay]
// A column on every bay boundary, centred on it; the last closes the row.
Corridor --> @RSX(END, BAY, CENTRE) [Pier] [Pier] [Pier]
             @SX(flo(1), COL) [] [@Grow(COL, 0, 0) Column]
Pier --> @SX(COL, flo(1)) [@Tr(-COL, 0, 0) @Grow(COL, 0, 0) Column] []
Column --> @SX(flo(1), COL, flo(1)) [] [@SZ(flo(1), COL, flo(1)) [] [;(17) @Cyl(16)] []] []
// The roof over the eaves, its slope the purlins' steps, tiles 0.45 apart.
Roof --> @Tr(-OV, 0, -OV) @Grow(2 * OV, 0, 2 * OV) ;(26) @Roof(HIP, 0.45, 0, JUJIA)
";

const BRACKETS: &str =
    "Brackets --> [;(19) @Tr(0.2, 0, 0.2) @Grow(-0.4, 0, -0.4) @Block] @Comp [BrkFace]
BrkFace --> @RX(BRK_PITCH) [BrkSet]
BrkSet --> @SX(flo(1), BRK_W, flo(1)) [] [@SY(flo(1), rel(0.7)) [] [;(18) @Ext(0.35) @Block]] []
";

const RAFTERS: &str = "Rafters --> @Comp [RafFace]
RafFace --> @RX(RAF_PITCH) [Rafter]
Rafter --> @SX(flo(1), RAF_W, flo(1)) [] [;(19) @Ext(OV + 0.1) @Block] []
";

const WALL: &str = "Wall --> ;(21) @Ext(0.25) @Block
";

const WINDOW: &str = "Window --> @SX(0.12, flo(1), 0.12) [;(17) @Ext(0.3) @Block] [Lattice] [;(17) @Ext(0.3) @Block]
Lattice --> [;(19) @Ext(0.05) @Block] @RX(0.3) [@SX(flo(1), 0.06, flo(1)) [] [;(17) @Ext(0.15) @Block] []]
";

const DOOR: &str = "Door --> @SX(rel(0.5), rel(0.5)) [Leaf] [Leaf]
Leaf --> @SX(0.1, flo(1), 0.1) [;(17) @Ext(0.3) @Block] [;(19) @Ext(0.12) @Block] [;(17) @Ext(0.3) @Block]
";
