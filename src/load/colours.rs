//! Load: a cpfg model's colour map (`.map`) and material (`.mat`) files,
//! named on the `cpfg` line of its `specifications` file (`cpfg -m
//! plant.map plant.l plant.v`, `-M plant.mat`). The files' bytes in, the
//! colour of each cpfg colour index out (sRGB, 0..=1), to be used instead
//! of lsys's palette.
//!
//! The formats, as cpfg and vlab's editors write them:
//! * a colour map is 256 entries of three bytes, red, green and blue
//!   (768 bytes); `-m` and `-m1` give indices 0..=255, `-m2` a second map,
//!   indices 256..=511;
//! * a material file is up to 256 records of 15 bytes: the index, the
//!   transparency, then ambient, diffuse, emission and specular colours
//!   (three bytes each) and the shininess. A material's colour here is its
//!   diffuse colour plus its emission (lsys draws one colour per index).

use std::path::Path;

use miette::Report;

use super::error::LoadError;
use super::include::IncludeFinder;

/// What a colour file holds: colour map or materials.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Map,
    Materials,
}

/// The colour files the first `cpfg` line of the model's `specifications`
/// text names: each with its kind and the first colour index it sets.
fn named_files(spec: &str) -> Vec<(Kind, usize, String)> {
    let mut out = Vec::new();
    let Some(words) = super::view::cpfg_lines(spec).next() else {
        return out;
    };
    let mut i = 0;
    while i < words.len() {
        let flag = match words[i] {
            "-m" | "-m1" => Some((Kind::Map, 0)),
            "-m2" => Some((Kind::Map, 256)),
            "-M" | "-M1" => Some((Kind::Materials, 0)),
            _ => None,
        };
        if let (Some((kind, first)), Some(file)) = (flag, words.get(i + 1)) {
            out.push((kind, first, file.to_string()));
            i += 1;
        }
        i += 1;
    }
    out
}

/// The colours of the colour map and material files of the model at
/// `model` (index, sRGB), as the model's `specifications` (read into
/// `sources` with the view file) names them, materials after maps so that they win; a file
/// that cannot be used is a warning and gives no colours.
pub(super) fn read_colour_files(
    model: &Path,
    finder: &IncludeFinder,
    sources: &crate::source::SourceMap,
) -> (Vec<(usize, [f32; 3])>, Vec<Report>) {
    let dir = model.parent().unwrap_or(Path::new("."));
    let mut files = super::view::specifications(model, sources).map_or(Vec::new(), named_files);
    files.sort_by_key(|f| f.0 == Kind::Materials);
    let mut colours = Vec::new();
    let mut warnings = Vec::new();
    for (kind, first, file) in files {
        let path = dir.join(&file);
        let parsed =
            finder
                .read_bytes(&path)
                .map_err(|r| r.message())
                .and_then(|bytes| match kind {
                    Kind::Map => parse_colour_map(&bytes),
                    Kind::Materials => parse_materials(&bytes),
                });
        match parsed {
            Ok(list) => colours.extend(list.into_iter().map(|(i, c)| (first + i, c))),
            Err(why) => warnings.push(Report::new(LoadError::ColourFile {
                path: path.display().to_string(),
                why,
            })),
        }
    }
    (colours, warnings)
}

/// A colour map's entries: three bytes each, at most 256.
pub fn parse_colour_map(bytes: &[u8]) -> Result<Vec<(usize, [f32; 3])>, String> {
    if bytes.is_empty() || bytes.len() % 3 != 0 || bytes.len() > 768 {
        return Err(format!(
            "a colour map is 256 colours of 3 bytes (768 bytes); this file has {} bytes",
            bytes.len()
        ));
    }
    Ok(bytes
        .chunks_exact(3)
        .enumerate()
        .map(|(i, c)| (i, [c[0], c[1], c[2]].map(|b| f32::from(b) / 255.0)))
        .collect())
}

/// A material file's records: 15 bytes each, at most 256; the index a
/// record sets is its first byte.
pub fn parse_materials(bytes: &[u8]) -> Result<Vec<(usize, [f32; 3])>, String> {
    if bytes.is_empty() || bytes.len() % 15 != 0 || bytes.len() > 15 * 256 {
        return Err(format!(
            "a material file is up to 256 materials of 15 bytes; this file has {} bytes",
            bytes.len()
        ));
    }
    Ok(bytes
        .chunks_exact(15)
        .map(|m| {
            let colour = [0, 1, 2].map(|k| {
                let diffuse = f32::from(m[5 + k]) / 255.0;
                let emission = f32::from(m[8 + k]) / 255.0;
                (diffuse + emission).min(1.0)
            });
            (usize::from(m[0]), colour)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_colour_map_is_rgb_triples() {
        let mut bytes = vec![0u8; 768];
        bytes[3..6].copy_from_slice(&[255, 0, 51]);
        let map = parse_colour_map(&bytes).unwrap();
        assert_eq!(map.len(), 256);
        assert_eq!(map[1], (1, [1.0, 0.0, 0.2]));
        assert!(parse_colour_map(&[0; 10]).unwrap_err().contains("10 bytes"));
    }

    #[test]
    fn a_material_is_its_diffuse_colour_plus_emission() {
        let mut m = [0u8; 30];
        m[15] = 7; // index
        m[15 + 5..15 + 8].copy_from_slice(&[204, 102, 0]);
        m[15 + 8] = 102; // emission red
        let mats = parse_materials(&m).unwrap();
        assert_eq!(mats[0], (0, [0.0, 0.0, 0.0]));
        assert_eq!(mats[1], (7, [1.0, 0.4, 0.0]));
        assert!(parse_materials(&[0; 16]).is_err());
    }
}
