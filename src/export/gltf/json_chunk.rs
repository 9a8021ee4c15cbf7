//! The glTF document -> its JSON text, exactly as serde_json writes it
//! (compact), with the node list written here: a Pailou has thousands of
//! nodes (every part of every Toukung it places) but only a few hundred
//! different matrices, so each matrix's text is made once and copied, and
//! a node's few fields are written without serde's machinery. Every other
//! part of the document, and any node with other fields, goes through
//! serde_json as before.

use std::collections::HashMap;

use gltf_json as json;
use rustc_hash::FxBuildHasher;

/// The name of the node that holds the node list's place while the rest
/// of the document is serialised. A name lsys never makes (module names
/// have no control characters), so its text occurs once.
const PLACEHOLDER: &str = "\u{0}lsys: the nodes go here\u{0}";

/// The compact JSON text of `root`, byte for byte what
/// `gltf_json::serialize::to_vec(root)` gives.
pub(super) fn to_vec(root: &mut json::Root) -> Result<Vec<u8>, serde_json::Error> {
    if root.nodes.is_empty() {
        return json::serialize::to_vec(root);
    }
    let nodes = std::mem::replace(
        &mut root.nodes,
        vec![json::Node {
            name: Some(PLACEHOLDER.to_string()),
            ..Default::default()
        }],
    );
    let rest = json::serialize::to_vec(root);
    root.nodes = nodes;
    let rest = rest?;
    let mut marker = b"\"nodes\":".to_vec();
    serde_json::to_writer(
        &mut marker,
        &[json::Node {
            name: Some(PLACEHOLDER.to_string()),
            ..Default::default()
        }],
    )?;
    let mut found = rest
        .windows(marker.len())
        .enumerate()
        .filter(|(_, w)| *w == marker.as_slice())
        .map(|(i, _)| i);
    let (Some(at), None) = (found.next(), found.next()) else {
        // Not where it was expected (cannot happen with lsys's names):
        // the plain way.
        return json::serialize::to_vec(root);
    };
    let mut out = Vec::with_capacity(rest.len() + 160 * root.nodes.len());
    out.extend_from_slice(&rest[..at]);
    out.extend_from_slice(b"\"nodes\":");
    write_nodes(&mut out, &root.nodes)?;
    out.extend_from_slice(&rest[at + marker.len()..]);
    Ok(out)
}

/// `nodes` as a JSON array, as serde_json writes it.
fn write_nodes(out: &mut Vec<u8>, nodes: &[json::Node]) -> Result<(), serde_json::Error> {
    // Where the text of each matrix met is in `out`, by its bits.
    let mut matrices: HashMap<[u32; 16], (usize, usize), FxBuildHasher> = HashMap::default();
    out.push(b'[');
    for (i, node) in nodes.iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        if !plain(node) {
            serde_json::to_writer(&mut *out, node)?;
            continue;
        }
        out.push(b'{');
        let mut first = true;
        let mut key = |out: &mut Vec<u8>, k: &str| {
            if !first {
                out.push(b',');
            }
            first = false;
            out.push(b'"');
            out.extend_from_slice(k.as_bytes());
            out.extend_from_slice(b"\":");
        };
        if let Some(children) = &node.children {
            key(out, "children");
            out.push(b'[');
            for (j, c) in children.iter().enumerate() {
                if j > 0 {
                    out.push(b',');
                }
                number(out, c.value());
            }
            out.push(b']');
        }
        if let Some(m) = &node.matrix {
            key(out, "matrix");
            match matrices.entry(m.map(f32::to_bits)) {
                std::collections::hash_map::Entry::Occupied(at) => {
                    let (start, end) = *at.get();
                    out.extend_from_within(start..end);
                }
                std::collections::hash_map::Entry::Vacant(slot) => {
                    let start = out.len();
                    write_matrix(out, m)?;
                    slot.insert((start, out.len()));
                }
            }
        }
        if let Some(mesh) = &node.mesh {
            key(out, "mesh");
            number(out, mesh.value());
        }
        if let Some(name) = &node.name {
            key(out, "name");
            serde_json::to_writer(&mut *out, name)?;
        }
        out.push(b'}');
    }
    out.push(b']');
    Ok(())
}

/// Whether `node` has only the fields lsys's placements use (children,
/// matrix, mesh, name), which [`write_nodes`] writes itself.
fn plain(node: &json::Node) -> bool {
    node.camera.is_none()
        && node.extensions.is_none()
        && node.rotation.is_none()
        && node.scale.is_none()
        && node.translation.is_none()
        && node.skin.is_none()
        && node.weights.is_none()
}

/// `m` as serde_json writes it, with 0, 1 and -1 (most of a placement's
/// matrix: its rotation's zeros, the 1 in the corner; 62 % of a Toukung's
/// 12,336 numbers) written as the text serde_json gives them without
/// formatting them: a Toukung's matrices are all different, and their
/// numbers were a quarter of its build.
fn write_matrix(out: &mut Vec<u8>, m: &[f32; 16]) -> Result<(), serde_json::Error> {
    out.push(b'[');
    for (i, v) in m.iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        // By bits: -0.0 is written as "-0.0".
        match v.to_bits() {
            0x0000_0000 => out.extend_from_slice(b"0.0"),
            0x3f80_0000 => out.extend_from_slice(b"1.0"),
            0xbf80_0000 => out.extend_from_slice(b"-1.0"),
            _ => serde_json::to_writer(&mut *out, v)?,
        }
    }
    out.push(b']');
    Ok(())
}

fn number(out: &mut Vec<u8>, n: usize) {
    out.extend_from_slice(itoa::Buffer::new().format(n).as_bytes());
}

#[cfg(test)]
mod tests {
    use super::*;
    use json::Index;

    fn node(name: &str) -> json::Node {
        json::Node {
            name: Some(name.to_string()),
            ..Default::default()
        }
    }

    /// The node list written here is serde_json's text, for every field
    /// lsys sets, names that need escaping, repeated and odd matrices, and
    /// a node with a field left to serde.
    #[test]
    fn export_json_is_serde_jsons() {
        let m = [
            1.0,
            0.0,
            -0.0,
            0.0,
            0.5,
            1e-7,
            3.402_823_5e38,
            0.0,
            0.1,
            0.2,
            0.3,
            0.0,
            -12.5,
            -1.0,
            1.0e10,
            1.0,
        ];
        let mut root = json::Root::default();
        let mesh = root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some("m".into()),
            primitives: Vec::new(),
            weights: None,
        });
        let a = root.push(node("a \"quoted\" \\ name\n\u{1}ü"));
        let b = root.push(json::Node {
            matrix: Some(m),
            mesh: Some(mesh),
            ..node("TM#1/MAn#3")
        });
        root.push(json::Node {
            matrix: Some(m),
            children: Some(vec![a, b]),
            ..node("TM#2")
        });
        root.push(json::Node {
            children: Some(Vec::new()),
            matrix: Some([f32::NAN; 16]),
            ..Default::default()
        });
        root.push(json::Node {
            translation: Some([1.0, 2.0, 3.0]),
            mesh: Some(mesh),
            ..node("moved")
        });
        root.push(json::Scene {
            extensions: None,
            extras: Default::default(),
            name: None,
            nodes: vec![Index::new(2)],
        });
        let expected = json::serialize::to_vec(&root).unwrap();
        assert_eq!(
            String::from_utf8(to_vec(&mut root).unwrap()).unwrap(),
            String::from_utf8(expected).unwrap()
        );
        assert_eq!(root.nodes.len(), 5, "the nodes are put back");
    }
}
