//! Collisions: a [`Scene`]'s component instances -> the pairs whose boxes
//! interpenetrate. Each instance is its component's unit box carried to
//! world space (an axis-aligned box around it); a pair collides when the
//! boxes share more than half of the smaller one's volume. Parts that touch
//! or sink a little into each other, as attached parts do, do not count.

use glam::Vec3;

use super::scene::Scene;

/// Fraction of the smaller box that must be shared to report a pair.
pub const SHARED: f32 = 0.5;

/// Two instances that interpenetrate, named `<symbol>#<n>`.
#[derive(Clone, Debug, PartialEq)]
pub struct Collision {
    pub a: String,
    pub b: String,
    /// Shared volume over the smaller box's volume, 0..=1.
    pub shared: f32,
}

/// Every colliding pair, in placement order of the first instance.
pub fn collisions(scene: &Scene) -> Vec<Collision> {
    let boxes: Vec<(Vec3, Vec3)> = scene
        .instances
        .iter()
        .map(|i| {
            let corners = (0..8).map(|k| {
                let c = Vec3::new(
                    if k & 1 == 0 { -0.5 } else { 0.5 },
                    if k & 2 == 0 { -0.5 } else { 0.5 },
                    if k & 4 == 0 { -0.5 } else { 0.5 },
                );
                i.transform.transform_point3(c)
            });
            super::scene::bounds_of(corners).expect("eight corners")
        })
        .collect();
    // Sweep along x: only boxes whose x ranges overlap are compared.
    let mut order: Vec<usize> = (0..boxes.len()).collect();
    order.sort_by(|&p, &q| boxes[p].0.x.total_cmp(&boxes[q].0.x));
    let name = |k: usize| {
        let i = &scene.instances[k];
        format!("{}#{}", scene.components[i.component].name, i.number)
    };
    let mut out = Vec::new();
    for (n, &p) in order.iter().enumerate() {
        let (lo_p, hi_p) = boxes[p];
        for &q in &order[n + 1..] {
            let (lo_q, hi_q) = boxes[q];
            if lo_q.x >= hi_p.x {
                break;
            }
            let overlap = (hi_p.min(hi_q) - lo_p.max(lo_q)).max(Vec3::ZERO);
            let shared = overlap.x * overlap.y * overlap.z;
            let vol = |lo: Vec3, hi: Vec3| {
                let d = hi - lo;
                d.x * d.y * d.z
            };
            let smaller = vol(lo_p, hi_p).min(vol(lo_q, hi_q));
            if smaller > 0.0 && shared / smaller > SHARED {
                let (a, b) = if p < q { (p, q) } else { (q, p) };
                out.push((a, b, shared / smaller));
            }
        }
    }
    out.sort_by_key(|x| (x.0, x.1));
    out.into_iter()
        .map(|(a, b, shared)| Collision {
            a: name(a),
            b: name(b),
            shared,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::scene::{Component, Instance, Part, TriMesh};
    use glam::Mat4;

    fn scene(placements: &[(f32, f32)]) -> Scene {
        let mut s = Scene::default();
        s.components.push(Component {
            name: "B".into(),
            parts: vec![Part {
                mesh: TriMesh::cuboid(Vec3::splat(-0.5), Vec3::splat(0.5)),
                material: None,
            }],
            origin: "test".into(),
        });
        for (n, &(x, size)) in placements.iter().enumerate() {
            s.instances.push(Instance {
                component: 0,
                transform: Mat4::from_translation(Vec3::new(x, 0.0, 0.0))
                    * Mat4::from_scale(Vec3::splat(size)),
                material: 0,
                number: n as u32,
            });
        }
        s
    }

    #[test]
    fn deep_overlaps_are_reported_and_touching_is_not() {
        // 0 and 1 touch; 2 sits inside 3; 4 overlaps 3 by a sliver.
        let s = scene(&[
            (0.0, 1.0),
            (1.0, 1.0),
            (10.0, 0.5),
            (10.0, 2.0),
            (11.9, 1.0),
        ]);
        let c = collisions(&s);
        assert_eq!(c.len(), 1, "{c:?}");
        assert_eq!((c[0].a.as_str(), c[0].b.as_str()), ("B#2", "B#3"));
        assert!((c[0].shared - 1.0).abs() < 1e-6);
    }
}
