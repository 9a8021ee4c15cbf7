//! Internodes as instances (`lsys build --instanced`): turtle [`Chain`]s
//! -> one unit cylinder component and one placement per straight segment
//! (translation to its start, rotation of +Y onto it, scale by its radius
//! and length), which glTF writes with `EXT_mesh_gpu_instancing` in 40
//! bytes a segment. Segments do not share rings, so joints show where a
//! chain bends: meant for plain line-like models; the default tubes stay
//! baked ([`super::tubes`]).

use glam::{Mat4, Quat, Vec3};

use super::scene::{Component, Part, TriMesh};
use super::tube::{straight, tube};
use super::tubes::Facets;
use crate::turtle::drawing::{Chain, TubePoint};

/// The component's name, as nodes and `--stats` show it.
pub const NAME: &str = "internode";

/// A closed cylinder of radius 1 around +Y from y = 0 to 1, with `sides`
/// facets, taking the placement's colour.
pub fn unit_cylinder(sides: u32) -> Component {
    let point = |y: f32| TubePoint {
        pos: Vec3::new(0.0, y, 0.0),
        radius: 1.0,
        up: Vec3::Z,
    };
    let mut mesh = TriMesh::default();
    let chain = Chain {
        colour: 0,
        points: smallvec::smallvec![point(0.0), point(1.0)],
    };
    tube(&chain, sides, &mut mesh);
    Component::new(
        NAME,
        "built-in",
        vec![Part {
            mesh,
            material: None,
        }],
    )
}

/// The facets of the one cylinder all segments share: those of the widest.
pub fn sides(chains: &[Chain], facets: &Facets) -> u32 {
    let widest = chains
        .iter()
        .flat_map(|c| c.points.iter().map(|p| p.radius))
        .fold(0.0, f32::max);
    facets.sides(widest)
}

/// Calls `place(transform)` for every segment of `chain`, a straight run
/// of equal width counted as one segment.
pub fn segments(chain: &Chain, mut place: impl FnMut(Mat4)) {
    let pts = &chain.points;
    let mut from = 0;
    for i in 1..pts.len() {
        if i + 1 < pts.len() && straight(&pts[from], &pts[i], &pts[i + 1]) {
            continue;
        }
        let (a, b) = (pts[from], pts[i]);
        from = i;
        let d = b.pos - a.pos;
        let length = d.length();
        let radius = a.radius.max(b.radius);
        let drawn = length > 0.0 && radius > 0.0;
        if !drawn {
            continue;
        }
        let rotation = Quat::from_rotation_arc(Vec3::Y, d / length);
        place(Mat4::from_scale_rotation_translation(
            Vec3::new(radius, length, radius),
            rotation,
            a.pos,
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::tube::tests::chain;

    #[test]
    fn a_segment_maps_the_unit_cylinder_onto_it() {
        let c = chain(
            &[Vec3::ZERO, Vec3::X, Vec3::X * 2.0, Vec3::new(2.0, 1.0, 0.0)],
            0.1,
        );
        let mut placed = Vec::new();
        segments(&c, |m| placed.push(m));
        // the straight run from 0 to 2X is one segment
        assert_eq!(placed.len(), 2);
        let top = placed[0].transform_point3(Vec3::Y);
        assert!(top.distance(Vec3::X * 2.0) < 1e-5, "{top}");
        let rim = placed[1].transform_point3(Vec3::new(1.0, 0.0, 0.0));
        assert!((rim.distance(Vec3::X * 2.0) - 0.1).abs() < 1e-5);
        let cylinder = unit_cylinder(6);
        assert_eq!(cylinder.triangle_count(), 2 * 6 + 2 * 6);
    }
}
