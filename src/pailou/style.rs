//! Styles: a Pailou style name `NP-NE-NR` and a type (ridge or pillar) ->
//! a [`Layout`]: which entrances exist and which decorations each carries,
//! the tables `exists[i, j]` and `dec[i, j, k]` of `grammar/std/pailou.lsys`.
//!
//! The paper (Sec. 5) names a Pailou by its pillars NP and entrances NE on
//! the ground and its roofs NR, traditionally NE = NP − 1 and NR one of
//! {0, NE, 2NE+1, 3NE}; its Table 3 also has NR = NE+1, 2NE and 3NE+1
//! Pailous. What each count means here (docs/pailou.md):
//!
//! | NR     | roofs |
//! |--------|-------|
//! | 0      | none |
//! | NE     | one on every entrance |
//! | NE+1   | one on every entrance; the central one carries an entrance above with the main roof |
//! | 2NE    | every entrance carries an entrance above; roofs on both levels |
//! | 2NE+1  | every entrance carries an entrance above with a roof; a clipped roof over every pillar |
//! | 3NE    | every entrance carries an entrance above with a roof, and clipped roofs on both its sides |
//! | 3NE+1  | roofs on both levels, and a clipped roof over every pillar |
//!
//! Where two rows give the same count (NE = 1: NE+1 = 2NE, 2NE+1 = 3NE),
//! the upper row is taken.

use std::fmt::{self, Write};

/// Entrances per half, the central one included (the table has one more
/// row, always empty, that the grammar reads past the last entrance).
pub const MAX_HALF: usize = 5;
/// Levels (the table has one more, always empty).
pub const MAX_LEVELS: usize = 3;
/// Decorations per entrance (see the grammar's header).
pub const KINDS: usize = 12;

/// Ridge type: eaves roofs with Toukungs; pillar type: clipped roofs, the
/// pillars rising above the roofs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PailouType {
    Ridge,
    Pillar,
}

impl PailouType {
    /// How graphs, styles and messages spell it.
    pub fn name(self) -> &'static str {
        match self {
            PailouType::Ridge => "ridge",
            PailouType::Pillar => "pillar",
        }
    }
}

/// Which entrances exist and what each carries, for one half (the grammar
/// mirrors it). Indices are 0-based here; the grammar's are 1-based.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Layout {
    pub exists: [[bool; MAX_LEVELS + 1]; MAX_HALF + 1],
    pub dec: [[[bool; KINDS]; MAX_LEVELS + 1]; MAX_HALF + 1],
}

/// Why a style cannot be built.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StyleError(pub String);

impl fmt::Display for StyleError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(&self.0)
    }
}

// Decoration kinds (the grammar's k).
pub const MIDDLE_TOUKUNGS: usize = 0;
pub const SIDE_TOUKUNGS: usize = 1;
pub const CLIPPED_ROOF: usize = 2;
pub const EAVES_ROOF: usize = 3;
pub const QUETI: usize = 4;
pub const YUNDAN: usize = 5;
pub const FLOWER_BOARD: usize = 6;
pub const PILLAR_BASE: usize = 7;
pub const SIDE_CLIPPED_ROOFS: usize = 8;
pub const INSCRIBED_BOARD: usize = 9;
pub const PILLAR_ROOF: usize = 10;
pub const PILLAR_TYPE: usize = 11;

/// Reads `NP-NE-NR`.
pub fn parse_style(s: &str) -> Result<(usize, usize, usize), StyleError> {
    let parts: Vec<Option<usize>> = s.split('-').map(|p| p.trim().parse().ok()).collect();
    match parts[..] {
        [Some(np), Some(ne), Some(nr)] => Ok((np, ne, nr)),
        _ => Err(StyleError(format!(
            "`{s}` is not a style NP-NE-NR (pillars, entrances, roofs), e.g. 4-3-7"
        ))),
    }
}

/// The canonical layout of a style.
pub fn layout(np: usize, ne: usize, nr: usize, kind: PailouType) -> Result<Layout, StyleError> {
    if ne == 0 || ne % 2 == 0 {
        return Err(StyleError(format!(
            "{ne} entrances: a symmetric Pailou has an odd number of entrances on the ground (1, 3, 5, ...), one of them central"
        )));
    }
    if np != ne + 1 {
        return Err(StyleError(format!(
            "{np} pillars for {ne} entrances: side by side, {ne} entrances stand on {} pillars",
            ne + 1
        )));
    }
    let half = ne.div_ceil(2);
    if half > MAX_HALF {
        return Err(StyleError(format!(
            "{ne} entrances: at most {} are supported",
            2 * MAX_HALF - 1
        )));
    }
    // (lower roof, upper entrance, pillar roofs, side clipped roofs)
    let (lower, upper, pillar_roofs, side_roofs, centre_only) = match nr {
        0 => (false, false, false, false, false),
        n if n == ne => (true, false, false, false, false),
        n if n == ne + 1 => (true, true, false, false, true),
        n if n == 2 * ne => (true, true, false, false, false),
        n if n == 2 * ne + 1 => (false, true, true, false, false),
        n if n == 3 * ne => (false, true, false, true, false),
        n if n == 3 * ne + 1 => (true, true, true, false, false),
        _ => {
            return Err(StyleError(format!(
                "{nr} roofs on {ne} entrances: the styles are NR = 0, NE ({ne}), NE+1 ({}), 2NE ({}), 2NE+1 ({}), 3NE ({}) or 3NE+1 ({}); see docs/pailou.md",
                ne + 1,
                2 * ne,
                2 * ne + 1,
                3 * ne,
                3 * ne + 1
            )))
        }
    };
    let mut l = Layout {
        exists: [[false; MAX_LEVELS + 1]; MAX_HALF + 1],
        dec: [[[false; KINDS]; MAX_LEVELS + 1]; MAX_HALF + 1],
    };
    let ridge = kind == PailouType::Ridge;
    let roof = |d: &mut [bool; KINDS]| {
        d[MIDDLE_TOUKUNGS] = true;
        d[SIDE_TOUKUNGS] = ridge;
        d[EAVES_ROOF] = ridge;
        d[CLIPPED_ROOF] = !ridge;
    };
    for i in 0..half {
        l.exists[i][0] = true;
        let d = &mut l.dec[i][0];
        d[QUETI] = true;
        d[YUNDAN] = true;
        d[FLOWER_BOARD] = true;
        d[PILLAR_BASE] = true;
        d[INSCRIBED_BOARD] = i == 0;
        d[PILLAR_TYPE] = !ridge;
        let has_upper = upper && (!centre_only || i == 0);
        if lower || (nr > 0 && !has_upper) {
            roof(d);
        }
        d[PILLAR_ROOF] = pillar_roofs;
        d[SIDE_CLIPPED_ROOFS] = side_roofs;
        if has_upper {
            l.exists[i][1] = true;
            roof(&mut l.dec[i][1]);
        }
    }
    Ok(l)
}

impl Layout {
    /// Roofs of the whole Pailou (both halves; the central entrance's
    /// roofs once), as the grammar places them.
    pub fn roofs(&self) -> usize {
        let mut n = 0;
        for (i, levels) in self.dec.iter().enumerate() {
            for (j, d) in levels.iter().enumerate() {
                if !self.exists[i][j] {
                    continue;
                }
                let per_half = if i == 0 { 1 } else { 2 };
                if d[EAVES_ROOF] || d[CLIPPED_ROOF] {
                    // centred on the entrance: once for the central one
                    n += if i == 0 { 1 } else { 2 };
                }
                if d[PILLAR_ROOF] {
                    n += 2; // the outer pillar of each half
                }
                if d[SIDE_CLIPPED_ROOFS] {
                    n += 2 * per_half;
                }
            }
        }
        n
    }

    /// Pillars standing on the ground.
    pub fn pillars(&self) -> usize {
        2 * self.exists.iter().filter(|e| e[0]).count()
    }

    /// The `<layout>` block of the grammar: the two table defines.
    pub fn defines(&self) -> String {
        let b = |x: bool| if x { "1" } else { "0" };
        let mut out = String::new();
        let _ = writeln!(
            out,
            "#define exists[1..{}, 1..{}] {{",
            MAX_HALF + 1,
            MAX_LEVELS + 1
        );
        let rows: Vec<String> = self
            .exists
            .iter()
            .map(|r| {
                format!(
                    "    {}",
                    r.iter().map(|&x| b(x)).collect::<Vec<_>>().join(", ")
                )
            })
            .collect();
        out.push_str(&rows.join(",\n"));
        out.push_str("\n}\n");
        let _ = writeln!(
            out,
            "#define dec[1..{}, 1..{}, 0..{}] {{",
            MAX_HALF + 1,
            MAX_LEVELS + 1,
            KINDS - 1
        );
        let rows: Vec<String> = self
            .dec
            .iter()
            .map(|levels| {
                let ls: Vec<String> = levels
                    .iter()
                    .map(|d| d.iter().map(|&x| b(x)).collect::<Vec<_>>().join(","))
                    .collect();
                format!("    {}", ls.join(",  "))
            })
            .collect();
        out.push_str(&rows.join(",\n"));
        out.push_str("\n}\n");
        out
    }

    /// The entrances of the layout chart (paper, Sec. 4.2, Fig. 9a), from
    /// the top level down and, in each, from the left end to the right:
    /// what the chart and the studio's coloured chart draw.
    pub fn entrances(&self) -> Vec<Entrance> {
        let half = self.exists.iter().filter(|e| e[0]).count();
        let mut out = Vec::new();
        for j in (0..=MAX_LEVELS).rev() {
            for k in 0..(2 * half).saturating_sub(1) {
                // From the left end: the left half mirrored, the centre, the right half.
                let (i, side) = if k + 1 >= half {
                    (k + 1 - half, if k + 1 == half { 0 } else { 1 })
                } else {
                    (half - 1 - k, -1)
                };
                if !self.exists[i][j] {
                    continue;
                }
                let d = &self.dec[i][j];
                out.push(Entrance {
                    i: i + 1,
                    j: j + 1,
                    side,
                    roof: if d[EAVES_ROOF] {
                        Roof::Eaves
                    } else if d[CLIPPED_ROOF] {
                        Roof::Clipped
                    } else {
                        Roof::None
                    },
                    side_clipped: d[SIDE_CLIPPED_ROOFS],
                    pillar_roof: d[PILLAR_ROOF],
                    toukungs: d[MIDDLE_TOUKUNGS] || d[SIDE_TOUKUNGS],
                    flower_board: d[FLOWER_BOARD],
                    inscribed_board: d[INSCRIBED_BOARD],
                });
            }
        }
        out
    }

    /// The layout chart (paper, Sec. 4.2) as text: one line per level from
    /// the top, the entrances of both halves from left to right.
    pub fn chart(&self) -> String {
        let half = self.exists.iter().filter(|e| e[0]).count();
        let entrances = self.entrances();
        let mut out = String::new();
        for j in (1..=MAX_LEVELS + 1).rev() {
            let level: Vec<&Entrance> = entrances.iter().filter(|e| e.j == j).collect();
            if level.is_empty() {
                continue;
            }
            let mut line = format!("level {j}  ");
            for k in 0..(2 * half).saturating_sub(1) {
                let at = |e: &&&Entrance| e.column(half) == k;
                let cell = match level.iter().find(at) {
                    Some(e) => {
                        let roof = match e.roof {
                            Roof::Eaves => "^",
                            Roof::Clipped => "-",
                            Roof::None => " ",
                        };
                        let extra = match (e.side_clipped, e.pillar_roof) {
                            (true, _) => "c",
                            (_, true) => "p",
                            _ => "",
                        };
                        format!("[G{}{}{roof}{extra}]", e.i, e.j)
                    }
                    None => "      ".to_string(),
                };
                line.push_str(&cell);
            }
            out.push_str(line.trim_end());
            out.push('\n');
        }
        out.push_str("G<i><j>: entrance i from the centre, level j; ^ eaves roof, - clipped roof,\nc clipped roofs beside the entrance above, p a clipped roof over the outer pillar\n");
        out
    }
}

/// The roof an entrance carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Roof {
    None,
    Eaves,
    Clipped,
}

/// One entrance of a layout.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entrance {
    /// From the centre: 1 is the central entrance (the paper's G1j).
    pub i: usize,
    /// The level: 1 is the ground.
    pub j: usize,
    /// -1 left of the centre, 0 the centre, 1 right.
    pub side: i32,
    pub roof: Roof,
    /// Clipped roofs beside the entrance above.
    pub side_clipped: bool,
    /// A clipped roof over the outer pillar.
    pub pillar_roof: bool,
    pub toukungs: bool,
    pub flower_board: bool,
    pub inscribed_board: bool,
}

impl Entrance {
    /// Its column in a chart of `half` entrances a side, from the left end.
    pub fn column(&self, half: usize) -> usize {
        let i = self.i - 1;
        match self.side {
            -1 => half - 1 - i,
            _ => half - 1 + i,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's Table 3 styles build with the roof and pillar counts
    /// their names promise.
    #[test]
    fn table_3_styles_have_their_roofs_and_pillars() {
        for style in [
            "2-1-2", "6-5-5", "4-3-3", "2-1-3", "4-3-7", "6-5-11", "2-1-1", "2-1-4", "4-3-4",
            "6-5-15", "8-7-7",
        ] {
            let (np, ne, nr) = parse_style(style).unwrap();
            for kind in [PailouType::Ridge, PailouType::Pillar] {
                let l = layout(np, ne, nr, kind).unwrap();
                assert_eq!(l.pillars(), np, "{style}");
                assert_eq!(l.roofs(), nr, "{style} {kind:?}");
            }
        }
    }

    #[test]
    fn layout_charts() {
        let mut out = String::new();
        for (style, kind) in [
            ("4-3-7", PailouType::Ridge),
            ("6-5-15", PailouType::Ridge),
            ("4-3-4", PailouType::Pillar),
        ] {
            let (np, ne, nr) = parse_style(style).unwrap();
            out.push_str(&format!(
                "{style} {kind:?}\n{}\n",
                layout(np, ne, nr, kind).unwrap().chart()
            ));
        }
        insta::assert_snapshot!(out);
    }

    #[test]
    fn impossible_styles_say_why() {
        assert!(layout(4, 2, 2, PailouType::Ridge)
            .unwrap_err()
            .0
            .contains("odd"));
        assert!(layout(5, 3, 3, PailouType::Ridge)
            .unwrap_err()
            .0
            .contains("4 pillars"));
        assert!(layout(4, 3, 5, PailouType::Ridge)
            .unwrap_err()
            .0
            .contains("NE+1 (4)"));
        assert!(parse_style("4-3").is_err());
    }
}
