//! `lsys infer DRAWING -o OUT.lsys [--tree OUT.json] [--strokes LINES]`: an elevation line
//! drawing -> a hall's shape grammar (and its labelled shape tree), with a
//! one-line summary and the regions it could not label on standard error.

use super::args::InferArgs;
use super::report::report;
use super::{EX_DATAERR, EX_IOERR, EX_NOINPUT, EX_OK, EX_SOFTWARE};
use crate::driver::{self, InferFailure, InferOptions};

pub(super) fn infer_cmd(a: &InferArgs, color: bool) -> i32 {
    let opts = InferOptions {
        gap: a.gap,
        scale: a.scale,
    };
    let inference = match driver::infer_drawing(&a.drawing, a.strokes.as_deref(), &a.labels, &opts)
    {
        Ok(i) => i,
        Err(e) => return failed(e, color),
    };
    if let Err(e) = driver::write_inference(&inference, &a.output, a.tree.as_deref()) {
        return failed(e, color);
    }
    let mut counts: Vec<String> = inference
        .counts()
        .iter()
        .map(|(_, plural, n)| format!("{n} {plural}"))
        .collect();
    if let Some(summary) = &inference.summary {
        counts.insert(0, summary.clone());
    }
    eprintln!(
        "lsys: {}: {}; wrote {}{}",
        a.drawing.display(),
        counts.join(", "),
        a.output.display(),
        a.tree
            .as_ref()
            .map_or(String::new(), |t| format!(" and {}", t.display()))
    );
    if !inference.build_defines.is_empty() {
        let d: Vec<String> = inference
            .build_defines
            .iter()
            .map(|(k, v)| format!("-D {k}={v}"))
            .collect();
        eprintln!(
            "lsys: build it with `lsys build {} {}`",
            a.output.display(),
            d.join(" ")
        );
    }
    for &i in &inference.missed {
        let c = &a.labels[i];
        let [x0, y0, x1, y1] = c.bbox;
        eprintln!(
            "lsys: warning: --label {x0},{y0},{x1},{y1}={}: no node of the tree has that box (see --tree); it was not applied",
            c.label
        );
    }
    for b in &inference.unlabelled {
        eprintln!(
            "lsys: warning: the region at x {}..{}, y {}..{} could not be labelled; the grammar leaves it out",
            b[0], b[2], b[1], b[3]
        );
    }
    EX_OK
}

fn failed(e: InferFailure, color: bool) -> i32 {
    match e {
        InferFailure::Drawing(e) => {
            let code = match &e {
                crate::driver::InferError::Unreadable { .. } => EX_NOINPUT,
                _ => EX_DATAERR,
            };
            report(&e, color);
            code
        }
        InferFailure::Grammar(d) => {
            eprint!("{}", d.render(color));
            eprintln!("lsys: internal error: the inferred grammar does not compile; this is a bug in lsys, please report it with the drawing");
            EX_SOFTWARE
        }
        InferFailure::Write(e) => {
            eprintln!("lsys: cannot write the grammar: {e}");
            EX_IOERR
        }
    }
}
