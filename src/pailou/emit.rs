//! The canonical component graph of a layout. Input: a [`Layout`] and its
//! type; output: its [`GraphDocument`] (one id per component: `P1R`,
//! `L11`, `TM12`...), and that document's text, which `lsys pailou
//! --emit-graph` prints and `graph::read` reads back to the same layout.

use super::document::GraphDocument;
use super::style::*;

/// The canonical graph of a layout, as TOML (what `--emit-graph` prints),
/// under the heading `title`.
pub fn emit(layout: &Layout, kind: PailouType, title: &str) -> String {
    document(layout, kind).write(&format!(
        "{title}: a Pailou as a component graph (docs/pailou.md)."
    ))
}

/// The canonical graph of a layout, as a document.
pub fn document(layout: &Layout, kind: PailouType) -> GraphDocument {
    let mut comps: Vec<(String, &str)> = Vec::new();
    let mut attach: Vec<(String, Vec<String>)> = Vec::new();
    let half = layout.exists.iter().filter(|e| e[0]).count();
    for side in ["R", "L"] {
        for i in 0..half {
            let e = |j: usize| -> String {
                if i == 0 {
                    format!("{}{}", i + 1, j + 1)
                } else {
                    format!("{}{}{side}", i + 1, j + 1)
                }
            };
            let outer = format!("P{}{side}", i + 1);
            let inner = if i == 0 {
                format!("P1{}", if side == "R" { "L" } else { "R" })
            } else {
                format!("P{i}{side}")
            };
            comps.push((outer.clone(), "pillar"));
            let mut below: Option<String> = None;
            for j in 0..=MAX_LEVELS {
                if !layout.exists[i][j] {
                    break;
                }
                let d = &layout.dec[i][j];
                let lintel = format!("L{}", e(j));
                // the central entrance's parts once, from the right half
                let own = i > 0 || side == "R";
                let supports = match &below {
                    None => vec![inner.clone(), outer.clone()],
                    Some(b) => {
                        let (a, c) = (format!("S{}a", e(j)), format!("S{}b", e(j)));
                        if own {
                            comps.push((a.clone(), "suspended_pillar"));
                            comps.push((c.clone(), "suspended_pillar"));
                            attach.push((a.clone(), vec![b.clone()]));
                            attach.push((c.clone(), vec![b.clone()]));
                        }
                        vec![a, c]
                    }
                };
                if own {
                    comps.push((lintel.clone(), "lintel"));
                    attach.push((lintel.clone(), supports));
                    let mut deco = |id: String, k: &'static str, to: String| {
                        comps.push((id.clone(), k));
                        attach.push((id, vec![to]));
                    };
                    if d[MIDDLE_TOUKUNGS] {
                        deco(format!("TM{}", e(j)), "middle_toukung", lintel.clone());
                    }
                    if d[SIDE_TOUKUNGS] {
                        deco(format!("TS{}", e(j)), "side_toukung", lintel.clone());
                    }
                    let roof_on = if d[MIDDLE_TOUKUNGS] {
                        format!("TM{}", e(j))
                    } else {
                        lintel.clone()
                    };
                    if d[EAVES_ROOF] {
                        deco(format!("RE{}", e(j)), "eaves_roof", roof_on.clone());
                    }
                    if d[CLIPPED_ROOF] {
                        deco(format!("RC{}", e(j)), "clipped_roof", roof_on);
                    }
                    if d[FLOWER_BOARD] {
                        deco(format!("FB{}", e(j)), "flower_board", lintel.clone());
                    }
                    if d[INSCRIBED_BOARD] {
                        deco(format!("IB{}", e(j)), "inscribed_board", lintel.clone());
                    }
                    if d[QUETI] {
                        deco(format!("Q{}", e(j)), "queti", lintel.clone());
                        if d[YUNDAN] {
                            deco(format!("Y{}", e(j)), "yundan", format!("Q{}", e(j)));
                        }
                    }
                }
                if j == 0 {
                    if d[PILLAR_BASE] {
                        comps.push((format!("B{}{side}", i + 1), "pillar_base"));
                        attach.push((format!("B{}{side}", i + 1), vec![outer.clone()]));
                    }
                    if d[PILLAR_ROOF] {
                        comps.push((format!("RP{}{side}", i + 1), "clipped_roof"));
                        attach.push((format!("RP{}{side}", i + 1), vec![outer.clone()]));
                    }
                }
                below = Some(lintel);
                let _ = d;
            }
        }
    }
    // Clipped roofs beside an entrance above stand on its suspended pillars.
    for (i, levels) in layout.dec.iter().enumerate() {
        if levels[0][SIDE_CLIPPED_ROOFS] && layout.exists[i][1] {
            for side in ["R", "L"] {
                if i == 0 && side == "L" {
                    continue;
                }
                let e = if i == 0 {
                    "12".to_string()
                } else {
                    format!("{}2{side}", i + 1)
                };
                for s in ["a", "b"] {
                    comps.push((format!("RS{e}{s}"), "clipped_roof"));
                    attach.push((format!("RS{e}{s}"), vec![format!("S{e}{s}")]));
                }
            }
        }
    }
    GraphDocument {
        kind: kind.name().to_string(),
        centre: "L11".to_string(),
        components: comps
            .into_iter()
            .map(|(id, k)| (id, k.to_string()))
            .collect(),
        attach,
        ..Default::default()
    }
}
