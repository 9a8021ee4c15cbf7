//! Load: the contour curves of a cpfg view file's `curve: FILE [SAMPLES]`
//! lines, numbered from 1 in order for `curveX/Y/Z(id, s)` and
//! `curveGAL(id)`. The view file's text in; each curve read (confined as
//! includes are, added to the source map so `lsys watch` sees it) and
//! parsed, or the reason it could not be, out.

use std::path::Path;

use super::include::IncludeFinder;
use crate::lang::curve::Curve;
use crate::source::{FileId, Origin, SourceFile, SourceMap};

/// cpfg's samples for the arc-length table when the line gives none.
const DEFAULT_SAMPLES: usize = 100;

/// Every `curve:` line of the view file `view_id` (at `view`), in order:
/// the curve, or why it cannot be used (reported where a model uses it).
pub(super) fn curves(
    view_id: FileId,
    view: &Path,
    finder: &IncludeFinder,
    sources: &mut SourceMap,
) -> Vec<Result<Curve, String>> {
    let dir = view.parent().unwrap_or(Path::new("."));
    let text = sources.get(view_id).text.clone();
    let mut out = Vec::new();
    for rest in super::view::keyed_lines(&text, "curve") {
        let mut words = rest.split_whitespace();
        let Some(file) = words.next() else {
            out.push(Err(
                "the view file's `curve:` line names no file".to_string()
            ));
            continue;
        };
        let samples = words
            .next()
            .and_then(|n| n.parse().ok())
            .unwrap_or(DEFAULT_SAMPLES);
        let path = dir.join(file);
        let body = match finder.read(&path) {
            Ok(b) => b,
            Err(r) => {
                out.push(Err(format!(
                    "cannot read {}: {}",
                    path.display(),
                    r.message()
                )));
                continue;
            }
        };
        sources.add(SourceFile::new(
            path.display().to_string(),
            Origin::Disk(path.clone()),
            body.clone(),
        ));
        out.push(
            Curve::parse(file, &body, samples).map_err(|e| format!("{}: {e}", path.display())),
        );
    }
    out
}
