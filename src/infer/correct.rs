//! The user's corrections (seed 003's interaction: "correct a label"): a
//! labelled shape tree and the labels the user gave to nodes, each named
//! by its box -> the same tree relabelled, and the corrections that found
//! no node.
//!
//! A node is named by its box because that is what the user saw and
//! clicked (the `--tree` JSON, the studio's overlay). A separator stroke
//! drawn after a correction can change the tree; a correction whose box is
//! gone is reported back, never applied to some other node.

use super::error::InferError;
use super::tree::Node;

/// The vocabulary of `--tree` (issue 33): every label a node may have.
pub const LABELS: [&str; 14] = [
    "platform", "stairs", "column", "bay", "door", "window", "wall", "lintel", "bracket", "rafter",
    "roof", "ridge", "ornament", "other",
];

/// "The node whose box is `bbox` is a `label`."
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Correction {
    pub bbox: [i32; 4],
    pub label: String,
}

/// The vocabulary's own spelling of `label`, or an error listing it.
pub fn known_label(label: &str) -> Result<&'static str, InferError> {
    LABELS
        .iter()
        .find(|l| **l == label)
        .copied()
        .ok_or_else(|| InferError::UnknownLabel {
            label: label.to_string(),
            known: LABELS.join(", "),
        })
}

/// Applies `corrections` in order; returns the indices of those whose box
/// is no node's. The highest node with the box is relabelled, and its
/// descendants that had its old label take the new one: a leaf filling its
/// piece shares the piece's box and goes with it, and a band read as
/// brackets and corrected to rafters holds rafters.
pub fn apply(root: &mut Node, corrections: &[Correction]) -> Result<Vec<usize>, InferError> {
    let mut missed = Vec::new();
    for (i, c) in corrections.iter().enumerate() {
        let label = known_label(&c.label)?;
        match node_with_box(root, c.bbox) {
            Some(node) => relabel(node, node.label, label),
            None => missed.push(i),
        }
    }
    Ok(missed)
}

fn node_with_box(n: &mut Node, bbox: [i32; 4]) -> Option<&mut Node> {
    if n.bbox == bbox {
        return Some(n);
    }
    n.children.iter_mut().find_map(|c| node_with_box(c, bbox))
}

fn relabel(n: &mut Node, old: &'static str, new: &'static str) {
    n.label = new;
    for c in &mut n.children {
        if c.label == old {
            relabel(c, old, new);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::infer::tree::Axis;

    fn node(label: &'static str, bbox: [i32; 4], children: Vec<Node>) -> Node {
        Node {
            label,
            bbox,
            split: (!children.is_empty()).then_some(Axis::X),
            repeat: false,
            children,
            regions: Vec::new(),
            fills: Vec::new(),
        }
    }

    fn band() -> Node {
        node(
            "bracket",
            [0, 0, 30, 10],
            vec![
                node("bracket", [0, 0, 10, 10], vec![]),
                node("other", [10, 0, 20, 10], vec![]),
                node(
                    "bracket",
                    [20, 0, 30, 10],
                    vec![node("bracket", [20, 0, 30, 10], vec![])],
                ),
            ],
        )
    }

    #[test]
    fn a_band_corrected_takes_its_pieces_along() {
        let mut b = band();
        let c = Correction {
            bbox: [0, 0, 30, 10],
            label: "rafter".into(),
        };
        assert_eq!(apply(&mut b, &[c]).unwrap(), Vec::<usize>::new());
        let labels: Vec<&str> = b.children.iter().map(|c| c.label).collect();
        assert_eq!(labels, ["rafter", "other", "rafter"]);
        assert_eq!(b.children[2].children[0].label, "rafter");
    }

    #[test]
    fn a_piece_corrected_takes_the_leaf_filling_it() {
        let mut b = band();
        let c = Correction {
            bbox: [20, 0, 30, 10],
            label: "other".into(),
        };
        apply(&mut b, &[c]).unwrap();
        assert_eq!(b.label, "bracket");
        assert_eq!(b.children[2].label, "other");
        assert_eq!(b.children[2].children[0].label, "other");
        assert_eq!(b.children[0].label, "bracket");
    }

    #[test]
    fn a_box_that_is_gone_is_reported_and_a_strange_label_refused() {
        let mut b = band();
        let gone = Correction {
            bbox: [5, 0, 15, 10],
            label: "door".into(),
        };
        assert_eq!(apply(&mut b, &[gone]).unwrap(), vec![0]);
        assert_eq!(b, band());
        let strange = Correction {
            bbox: [0, 0, 10, 10],
            label: "Door".into(),
        };
        let e = apply(&mut b, &[strange]).unwrap_err();
        assert!(e.to_string().contains("\"Door\""), "{e}");
    }
}
