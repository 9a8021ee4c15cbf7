//! Pailou builds read back from their GLB files: the placed parts by name,
//! with their world transforms or their boxes.

use std::path::PathBuf;

use glam::{Mat4, Vec3};

use super::{lsys, stderr};

/// The example graphs, sorted by name.
pub fn examples() -> Vec<PathBuf> {
    super::files("examples/pailou", "toml")
}

/// Builds `args` to a GLB and returns its placements: (name, world
/// transform). The nodes inside a nested component (`TS#1/MCa#0`, see
/// docs/pailou.md) follow their placement and are left out.
pub fn nodes(args: &[&str]) -> Vec<(String, Mat4)> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p.glb");
    let mut full: Vec<&str> = args.to_vec();
    full.extend(["-o", out.to_str().unwrap()]);
    let o = lsys(&full);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    let doc = gltf::Gltf::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    // Instances are children of the scene's root nodes; compose parents.
    let mut found = Vec::new();
    fn walk(n: gltf::Node, parent: Mat4, found: &mut Vec<(String, Mat4)>) {
        let m = parent * Mat4::from_cols_array_2d(&n.transform().matrix());
        if let Some(name) = n.name().filter(|name| !name.contains('/')) {
            found.push((name.to_string(), m));
        }
        for c in n.children() {
            walk(c, m, found);
        }
    }
    for s in doc.scenes() {
        for n in s.nodes() {
            walk(n, Mat4::IDENTITY, &mut found);
        }
    }
    found
}

/// The world box (min, max) of a placed component: its unit box is
/// centred on its node's origin, scaled along the node's axes.
pub fn unit_box(m: &Mat4) -> (Vec3, Vec3) {
    let size = Vec3::new(m.x_axis.length(), m.y_axis.length(), m.z_axis.length());
    let centre = m.w_axis.truncate();
    (centre - size / 2.0, centre + size / 2.0)
}

/// Boxes (min, max) of the placed parts of a build, by name (`MIB#0`):
/// a placed component's unit box is centred on its node's origin.
pub fn boxes(args: &[&str]) -> Vec<(String, Vec3, Vec3)> {
    nodes(args)
        .into_iter()
        .map(|(n, m)| {
            let (lo, hi) = unit_box(&m);
            (n, lo, hi)
        })
        .collect()
}
