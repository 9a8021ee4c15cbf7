//! The drawing round trip on Pailou fronts, measured (issue 33, item 5).
//!
//! Input: the Pailou styles of `lsys pailou` (every NP-NE-NR of Table 3's
//! kinds, both types), sampled with their proportions by a seeded
//! generator. Each is drawn as `lsys render --view front --style lines
//! --size 1000x600` draws its `--emit-lsys` grammar, read back as `lsys
//! infer` reads it (the driver, which reads a Pailou's front by synthesis:
//! src/driver/infer_pailou.rs), also after three kinds of damage, and
//! compared with what the generator built: its style and type, the counts
//! of pillars, roofs, bracket sets and entrances, the side entrances'
//! ratio, and each label's pixels (IoU).
//!
//! Output: `docs/drawing-roundtrip-pailou.md` (or `--out FILE`).
//!
//! ```text
//! cargo run --release --example pailou_roundtrip             # 200 drawings
//! cargo run --release --example pailou_roundtrip -- --quick  # 20, to stdout
//!     [--count N] [--seed S] [--out FILE]
//! ```

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use lsys::driver::{run, Pailou, PailouType};
use lsys::internals::export::render::{render, Image, PixelFrame, RenderOptions, Style, View};
use lsys::internals::infer::Node;
use lsys::Grammar;

#[path = "common/roundtrip.rs"]
mod roundtrip;
use roundtrip::{damaged, measure_all, png_bytes, read, Mask, SplitMix, CONDITIONS};

const DOC: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/docs/drawing-roundtrip-pailou.md"
);
const SIZE: (u32, u32) = (1000, 600);
const SEED: u64 = 34;
const FULL: usize = 200;
const QUICK: usize = 20;

/// The styles sampled: Table 3's and the layout rules' other roof counts.
const STYLES: [&str; 13] = [
    "2-1-1", "2-1-2", "2-1-3", "2-1-4", "4-3-3", "4-3-4", "4-3-7", "4-3-10", "6-5-5", "6-5-11",
    "6-5-15", "8-7-7", "8-7-22",
];

/// The sampled proportions: name, low, high (uniform, rounded to 0.01;
/// NTL a whole number). Table 3 keeps αSide from 0.7 to 1 and αUp about
/// 1/2; ω only scales the whole.
const PARAMS: [(&str, f64, f64); 5] = [
    ("ω", 8.0, 11.0),
    ("αSide", 0.65, 0.95),
    ("αUp", 0.4, 0.6),
    ("αEW", 0.7, 0.95),
    ("NTL", 3.0, 7.99),
];

/// Labels whose pixels are compared.
const IOU_LABELS: [&str; 4] = ["column", "roof", "bracket", "lintel"];

#[derive(Clone, Debug)]
struct Sample {
    style: &'static str,
    kind: PailouType,
    values: [f64; 5],
}

impl Sample {
    fn draw_from(rng: &mut SplitMix) -> Sample {
        let style = STYLES[(rng.next() % STYLES.len() as u64) as usize];
        let kind = if rng.next() % 2 == 0 {
            PailouType::Ridge
        } else {
            PailouType::Pillar
        };
        let mut values = [0.0; 5];
        for (v, (name, lo, hi)) in values.iter_mut().zip(PARAMS) {
            let x = lo + (hi - lo) * rng.unit();
            *v = if name == "NTL" {
                x.floor()
            } else {
                (x * 100.0).round() / 100.0
            };
        }
        Sample {
            style,
            kind,
            values,
        }
    }

    fn kind_name(&self) -> &'static str {
        match self.kind {
            PailouType::Ridge => "ridge",
            PailouType::Pillar => "pillar",
        }
    }

    fn shown(&self) -> String {
        let mut s = format!("{} {}", self.style, self.kind_name());
        for ((name, ..), v) in PARAMS.iter().zip(self.values) {
            let _ = write!(s, " {name}={v}");
        }
        s
    }
}

/// What the generator built, as counted from its placed parts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Counts {
    pillars: usize,
    roofs: usize,
    brackets: usize,
    bays: usize,
}

/// Boxes of the parts of `scene` in the picture's pixels, by label.
fn part_boxes(
    scene: &lsys::internals::mesh::Scene,
    frame: &PixelFrame,
) -> Vec<(&'static str, [f64; 4])> {
    frame
        .instance_boxes(scene)
        .into_iter()
        .filter_map(|(name, b)| {
            let label = match name {
                "MP" => "column",
                "RE" | "RC" => "roof",
                "TM" | "TS" => "bracket",
                "ML" | "MLO" | "MLS" => "lintel",
                _ => return None,
            };
            Some((label, b))
        })
        .collect()
}

/// Draws `s` as the command line does; the picture, the generator's
/// counts and its parts' boxes.
type Drawn = (Image, Counts, Vec<(&'static str, [f64; 4])>);

fn draw(s: &Sample) -> Result<Drawn, String> {
    let p = Pailou::style(s.style, s.kind).map_err(|e| e.to_string())?;
    let mut o = Grammar::options();
    for ((name, ..), v) in PARAMS.iter().zip(s.values) {
        o = o.define(name, v);
    }
    let done = run(&p.job(o), &mut |_| {}).map_err(|e| format!("{e:?}"))?;
    let scene = done.scene.mesh();
    let opts = RenderOptions {
        view: View::Front,
        style: Style::Lines,
        width: SIZE.0,
        height: SIZE.1,
        ..RenderOptions::default()
    };
    let image = render(scene, &opts);
    let frame = PixelFrame::of(scene, &opts).ok_or("nothing drawn")?;
    let boxes = part_boxes(scene, &frame);
    let named = |names: &[&str]| {
        scene
            .instances
            .iter()
            .filter(|i| names.contains(&scene.components[i.component].name.as_str()))
            .count()
    };
    let ne: usize = s
        .style
        .split('-')
        .nth(1)
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    let counts = Counts {
        pillars: named(&["MP"]),
        roofs: named(&["RE", "RC"]),
        brackets: named(&["TM", "TS"]),
        bays: ne,
    };
    Ok((image, counts, boxes))
}

fn count(n: &Node, label: &str) -> usize {
    usize::from(n.children.is_empty() && n.label == label)
        + n.children.iter().map(|c| count(c, label)).sum::<usize>()
}

fn leaf_boxes(n: &Node, label: &str, out: &mut Vec<[f64; 4]>) {
    if n.children.is_empty() && n.label == label {
        out.push(n.bbox.map(f64::from));
    }
    for c in &n.children {
        leaf_boxes(c, label, out);
    }
}

/// IoU of the unions of two sets of boxes, over the picture's pixels.
fn iou(a: &[[f64; 4]], b: &[[f64; 4]]) -> Option<f64> {
    let mask = |boxes: &[[f64; 4]]| {
        let mut m = Mask::new(SIZE.0 as usize, SIZE.1 as usize);
        boxes.iter().for_each(|b| m.add(*b));
        m
    };
    mask(a).iou(&mask(b))
}

/// One drawing read in one condition.
#[derive(Clone, Debug, Default)]
struct Reading {
    error: Option<String>,
    style: Option<String>,
    pillar_type: Option<String>,
    levels: Option<f64>,
    counts: Counts,
    side: Option<f64>,
    iou: Vec<Option<f64>>,
    ms: f64,
}

struct Outcome {
    sample: Sample,
    truth: Counts,
    readings: Vec<Reading>,
}

fn measure(k: usize, sample: Sample) -> Result<Outcome, String> {
    let (image, truth, boxes) = draw(&sample)?;
    let mut readings = Vec::new();
    for (c, condition) in CONDITIONS.iter().enumerate() {
        let picture = damaged(&image, condition, 1000 * k as u64 + c as u64);
        let name = format!("pailou-{k}-{condition}.png");
        let t = Instant::now();
        let inference = read(&png_bytes(&picture), &name);
        let ms = t.elapsed().as_secs_f64() * 1000.0;
        let inference = match inference {
            Ok(i) => i,
            Err(e) => {
                readings.push(Reading {
                    error: Some(e),
                    ms,
                    ..Reading::default()
                });
                continue;
            }
        };
        let Some(summary) = &inference.summary else {
            readings.push(Reading {
                error: Some("read as a hall".into()),
                ms,
                ..Reading::default()
            });
            continue;
        };
        let style = summary
            .split("style ")
            .nth(1)
            .and_then(|r| r.split(',').next())
            .map(str::to_string);
        let pillar_type = summary
            .split(", ")
            .nth(1)
            .and_then(|r| r.split(" type").next())
            .map(str::to_string);
        let levels = inference
            .build_defines
            .iter()
            .find(|(k, _)| k == "TM.NTL")
            .and_then(|(_, v)| v.parse().ok());
        let side = inference
            .grammar
            .lines()
            .find(|l| l.starts_with("#define side[1..6]"))
            .and_then(|l| l.split(['{', ',']).nth(1))
            .and_then(|v| v.trim().parse().ok());
        let root = &inference.tree;
        let iou = IOU_LABELS
            .iter()
            .map(|label| {
                let truth: Vec<[f64; 4]> = boxes
                    .iter()
                    .filter(|(l, _)| l == label)
                    .map(|(_, b)| *b)
                    .collect();
                let mut got = Vec::new();
                leaf_boxes(root, label, &mut got);
                iou(&truth, &got)
            })
            .collect();
        readings.push(Reading {
            error: None,
            style,
            pillar_type,
            levels,
            counts: Counts {
                pillars: count(root, "column"),
                roofs: count(root, "roof"),
                brackets: count(root, "bracket"),
                bays: count(root, "bay"),
            },
            side,
            iou,
            ms,
        });
    }
    Ok(Outcome {
        sample,
        truth,
        readings,
    })
}

fn pct(n: usize, of: usize) -> String {
    if of == 0 {
        "–".into()
    } else {
        format!("{:.1} %", 100.0 * n as f64 / of as f64)
    }
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

const USAGE: &str = "cargo run --release --example pailou_roundtrip -- [--quick] [--count N] [--seed S] [--out FILE]";

fn main() {
    let mut args = std::env::args().skip(1);
    let (mut n, mut seed, mut out, mut quick) = (FULL, SEED, None, false);
    while let Some(a) = args.next() {
        let mut value = |what: &str| args.next().unwrap_or_else(|| panic!("{a} needs {what}"));
        match a.as_str() {
            "--quick" => {
                quick = true;
                n = QUICK;
            }
            "--count" => n = value("a number").parse().expect("--count N"),
            "--seed" => seed = value("a number").parse().expect("--seed S"),
            "--out" => out = Some(PathBuf::from(value("a file"))),
            "--help" | "-h" => {
                println!("{USAGE}");
                return;
            }
            other => {
                eprintln!("pailou_roundtrip: unknown argument {other:?}\n{USAGE}");
                std::process::exit(2);
            }
        }
    }
    let out = out.or_else(|| (!quick).then(|| PathBuf::from(DOC)));
    let mut rng = SplitMix(seed);
    let samples: Vec<Sample> = (0..n).map(|_| Sample::draw_from(&mut rng)).collect();
    let results = measure_all("pailou_roundtrip", n, |k| measure(k, samples[k].clone()));
    let mut outcomes = Vec::new();
    let mut unbuilt = Vec::new();
    for (k, r) in results.into_iter().enumerate() {
        match r {
            Ok(o) => outcomes.push((k, o)),
            Err(e) => unbuilt.push((k, e)),
        }
    }
    let doc = report(seed, n, &outcomes, &unbuilt);
    match out {
        Some(path) => {
            std::fs::write(&path, doc).expect("the document is written");
            eprintln!("pailou_roundtrip: wrote {}", path.display());
        }
        None => print!("{doc}"),
    }
}

fn report(
    seed: u64,
    n: usize,
    outcomes: &[(usize, Outcome)],
    unbuilt: &[(usize, String)],
) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# The drawing round trip on Pailou fronts, measured\n\n\
         Generated by `cargo run --release --example pailou_roundtrip` \
         ([examples/pailou_roundtrip.rs](../examples/pailou_roundtrip.rs)); every number below \
         comes from that run. {n} Pailous sampled with seed {seed}, {} drawn and read{}. \
         The halls' round trip is [drawing-roundtrip.md](drawing-roundtrip.md); how a Pailou's \
         front is read is in [drawing.md](drawing.md), \"Pailou fronts\".\n",
        outcomes.len(),
        if unbuilt.is_empty() {
            String::new()
        } else {
            format!(" ({} did not build)", unbuilt.len())
        }
    );
    let _ = writeln!(
        s,
        "## How\n\n\
         * **Pailous.** A style drawn uniformly from {} (both types, uniformly), and \
         its proportions uniformly in these ranges (rounded to 0.01; NTL a whole number), \
         passed as `-D` to the style's grammar:\n",
        STYLES.map(|st| format!("`{st}`")).join(", ")
    );
    let _ = writeln!(s, "  | define | from | to |\n  |---|---|---|");
    for (name, lo, hi) in PARAMS {
        let hi = if name == "NTL" { hi.floor() } else { hi };
        let _ = writeln!(s, "  | {name} | {lo} | {hi} |");
    }
    let _ = writeln!(
        s,
        "\n* **Drawings.** Each built and drawn as `lsys pailou --style S --type T --emit-lsys` \
         then `lsys render --view front --style lines --size {}x{}` draw it, and read by \
         `lsys::driver::infer_edited` as `lsys infer` reads it (defaults). Damage as in \
         [drawing-roundtrip.md](drawing-roundtrip.md): gaps, jitter, blur.\n\
         * **Truth.** The generator's placed parts: pillars (`MP`, the ground's and the \
         suspended ones), roofs (`RE`, `RC`), bracket sets (`TM`, `TS`), lintels (`ML`, `MLO`, \
         `MLS`); bays are the style's NE ground entrances. Their boxes are projected with the \
         renderer's own framing (`PixelFrame`). A reading is right for a count when the tree has \
         exactly that many leaves so labelled; for the style when it names the generator's \
         NP-NE-NR and type; for the Toukung levels when the `TM.NTL` it builds with is the \
         sampled NTL. \"All\" asks style, type and the four counts (not the levels).\n\
         * **Side ratio.** The grammar's first `side[1..6]` entry, each side entrance's width over \
         the inner one's as measured, against the sampled αSide.\n",
        SIZE.0, SIZE.1
    );
    // Exact counts.
    let _ = writeln!(
        s,
        "## Style and counts\n\n\
         Share of drawings read with exactly the generator's value. Unread: not read as a Pailou.\n\n\
         | drawing | n | unread | style | type | style and type | Toukung levels | pillars | roofs | bracket sets | bays | all |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for (c, condition) in CONDITIONS.iter().enumerate() {
        let rs: Vec<(&Outcome, &Reading)> =
            outcomes.iter().map(|(_, o)| (o, &o.readings[c])).collect();
        let m = rs.len();
        let ok = |f: &dyn Fn(&Outcome, &Reading) -> bool| {
            rs.iter()
                .filter(|(o, r)| r.error.is_none() && f(o, r))
                .count()
        };
        let style = |o: &Outcome, r: &Reading| r.style.as_deref() == Some(o.sample.style);
        let kind =
            |o: &Outcome, r: &Reading| r.pillar_type.as_deref() == Some(o.sample.kind_name());
        let _ = writeln!(
            s,
            "| {condition} | {m} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            rs.iter().filter(|(_, r)| r.error.is_some()).count(),
            pct(ok(&style), m),
            pct(ok(&kind), m),
            pct(ok(&|o, r| style(o, r) && kind(o, r)), m),
            pct(ok(&|o, r| r.levels == Some(o.sample.values[4])), m),
            pct(ok(&|o, r| r.counts.pillars == o.truth.pillars), m),
            pct(ok(&|o, r| r.counts.roofs == o.truth.roofs), m),
            pct(ok(&|o, r| r.counts.brackets == o.truth.brackets), m),
            pct(ok(&|o, r| r.counts.bays == o.truth.bays), m),
            pct(
                ok(&|o, r| style(o, r) && kind(o, r) && r.counts == o.truth),
                m
            ),
        );
    }
    // Side ratio and IoU.
    let _ = writeln!(
        s,
        "\n## Side ratio and IoU per label\n\n\
         Side ratio: |measured − sampled αSide| over the drawings with side entrances that were \
         read; IoU: mean over the drawings read (n where it is not all of them).\n\n\
         | drawing | side ratio: mean error | max error | {} | median time per drawing |\n\
         |---|---|---|{}---|",
        IOU_LABELS.join(" | "),
        "---|".repeat(IOU_LABELS.len())
    );
    for (c, condition) in CONDITIONS.iter().enumerate() {
        let errs: Vec<f64> = outcomes
            .iter()
            .filter_map(|(_, o)| {
                let side = o.readings[c].side?;
                // a 2-pillar Pailou has no side entrance to measure
                (!o.sample.style.starts_with("2-")).then(|| (side - o.sample.values[1]).abs())
            })
            .collect();
        let mean = errs.iter().sum::<f64>() / errs.len().max(1) as f64;
        let max = errs.iter().copied().fold(0.0, f64::max);
        let mut cells = Vec::new();
        for l in 0..IOU_LABELS.len() {
            let v: Vec<f64> = outcomes
                .iter()
                .filter_map(|(_, o)| o.readings[c].iou.get(l).copied().flatten())
                .collect();
            let mean = v.iter().sum::<f64>() / v.len().max(1) as f64;
            cells.push(if v.len() == outcomes.len() {
                format!("{mean:.3}")
            } else {
                format!("{mean:.3} (n {})", v.len())
            });
        }
        let mut times: Vec<f64> = outcomes.iter().map(|(_, o)| o.readings[c].ms).collect();
        let _ = writeln!(
            s,
            "| {condition} | {mean:.3} (n {}) | {max:.3} | {} | {:.0} ms |",
            errs.len(),
            cells.join(" | "),
            median(&mut times)
        );
    }
    // Failures.
    let _ = writeln!(
        s,
        "\n## Failures\n\nDrawings read wrong (style, type or a count), by condition: got / expected.\n"
    );
    for (c, condition) in CONDITIONS.iter().enumerate() {
        let wrong: Vec<String> = outcomes
            .iter()
            .filter_map(|(k, o)| {
                let r = &o.readings[c];
                let right = r.error.is_none()
                    && r.style.as_deref() == Some(o.sample.style)
                    && r.pillar_type.as_deref() == Some(o.sample.kind_name())
                    && r.counts == o.truth;
                (!right).then(|| {
                    let got = match &r.error {
                        Some(e) => e.clone(),
                        None => format!(
                            "{} {}; {}, {}, {}, {}",
                            r.style.as_deref().unwrap_or("?"),
                            r.pillar_type.as_deref().unwrap_or("?"),
                            r.counts.pillars,
                            r.counts.roofs,
                            r.counts.brackets,
                            r.counts.bays
                        ),
                    };
                    format!(
                        "| {k} | {} | {got} | {}, {}, {}, {} |",
                        o.sample.shown(),
                        o.truth.pillars,
                        o.truth.roofs,
                        o.truth.brackets,
                        o.truth.bays
                    )
                })
            })
            .collect();
        let _ = writeln!(s, "### {condition} ({})\n", wrong.len());
        if !wrong.is_empty() {
            let _ = writeln!(
                s,
                "| drawing | sampled | got (style type; pillars, roofs, bracket sets, bays) | expected |\n|---|---|---|---|"
            );
            for line in wrong.iter().take(40) {
                let _ = writeln!(s, "{line}");
            }
            if wrong.len() > 40 {
                let _ = writeln!(s, "\n({} more)", wrong.len() - 40);
            }
            let _ = writeln!(s);
        }
    }
    for (k, e) in unbuilt {
        let _ = writeln!(s, "* drawing {k} did not build: {e}");
    }
    s
}
