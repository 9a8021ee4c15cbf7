//! The colour palette: turtle colour indices (`;`, `,`, `'`) -> sRGB
//! colours. Sixteen defaults chosen for plants and timber architecture;
//! a file overrides entries with `colour i: #rrggbb`. Indices past the
//! last entry wrap around.

/// The default palette, sRGB.
pub const DEFAULT: [(&str, [u8; 3]); 16] = [
    ("bark", [0x6b, 0x4f, 0x2a]),
    ("leaf", [0x3f, 0x7f, 0x2f]),
    ("light-green", [0x8f, 0xbf, 0x3f]),
    ("straw", [0xd9, 0xc2, 0x7a]),
    ("red", [0xc0, 0x39, 0x2b]),
    ("orange", [0xe8, 0xa3, 0x3c]),
    ("yellow", [0xf1, 0xd5, 0x4b]),
    ("white", [0xf4, 0xf4, 0xf0]),
    ("blue", [0x2e, 0x6f, 0xb5]),
    ("purple", [0x7d, 0x4f, 0xa8]),
    ("grey", [0x8a, 0x8a, 0x8a]),
    ("charcoal", [0x30, 0x30, 0x30]),
    ("timber", [0xa0, 0x52, 0x2d]),
    ("lacquer", [0xb2, 0x22, 0x22]),
    ("gold", [0xd4, 0xaf, 0x37]),
    ("glaze", [0x2f, 0x6f, 0x6f]),
];

/// A palette: the defaults with a file's overrides.
#[derive(Clone, Debug, Default)]
pub struct Palette {
    overrides: Vec<(usize, [f32; 3])>,
}

impl Palette {
    pub fn new(overrides: &[(usize, [f32; 3])]) -> Self {
        Palette {
            overrides: overrides.to_vec(),
        }
    }

    /// The material name and sRGB colour of index `i`.
    pub fn colour(&self, i: u32) -> (String, [f32; 3]) {
        let i = i as usize;
        if let Some(&(_, rgb)) = self.overrides.iter().rev().find(|(j, _)| *j == i) {
            return (format!("colour{i}"), rgb);
        }
        let (name, c) = DEFAULT[i % DEFAULT.len()];
        (format!("colour{i}-{name}"), c.map(|x| x as f32 / 255.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overrides_win_and_indices_wrap() {
        let p = Palette::new(&[(3, [1.0, 0.0, 0.0])]);
        assert_eq!(p.colour(3).1, [1.0, 0.0, 0.0]);
        assert_eq!(p.colour(17).1, p.colour(1).1);
        assert_ne!(p.colour(0).1, p.colour(1).1);
    }
}
