//! What the turtle draws, before meshing: tube segments grouped in chains,
//! polygons, spheres and discs, generalized-cylinder curves and component
//! placements. Input: turtle commands; output: plain records that the mesh
//! builder turns into a [`Scene`](crate::mesh::Scene) and that tests print.

use std::fmt::Write;

use glam::{Mat4, Vec3};

use crate::resolve::ir::SymId;

/// One point of a tube's centre line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TubePoint {
    pub pos: Vec3,
    /// Half the line width at this point.
    pub radius: f32,
    /// The turtle's up vector here: orients the first ring so that tubes do
    /// not twist.
    pub up: Vec3,
}

/// A connected run of drawn segments with one colour: one tube with shared
/// rings between consecutive segments, capped at both ends.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    pub colour: u32,
    pub points: ChainPoints,
}

/// A chain's points. Most chains of a branching model are a single
/// segment: two points are kept inline, not in an allocation of their own
/// (W2 draws 262,143 chains).
pub type ChainPoints = smallvec::SmallVec<[TubePoint; 2]>;

/// Where a chain starts: the point of an earlier chain the turtle stood
/// on when it drew the chain's first segment (a branch leaving its
/// parent). Meshing checks it before use: it only saves looking the point
/// up by position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Origin {
    pub chain: u32,
    pub point: u32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    pub colour: u32,
    pub points: Vec<Vec3>,
    /// Texture coordinates, one per point, when a `@Tex` projection
    /// covers it (a block's face).
    pub uv: Option<Box<Uv>>,
}

/// A polygon's place in a texture (solid.rs, `Projection`).
#[derive(Clone, Debug, PartialEq)]
pub struct Uv {
    /// The `texture i:` index.
    pub texture: u32,
    /// glTF's coordinates: (0, 0) the image's top left.
    pub coords: Vec<glam::Vec2>,
}

pub use crate::lang::commands::ShapeKind;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shape {
    pub kind: ShapeKind,
    pub centre: Vec3,
    /// The turtle's heading: the normal of discs and circles.
    pub normal: Vec3,
    pub radius: f32,
    pub colour: u32,
}

/// A component placement `~X(s)` / `~X(sx,sy,sz)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub symbol: SymId,
    /// Unit-box component space to world space.
    pub transform: Mat4,
    pub colour: u32,
    /// Index of the module in the derived string, for error messages.
    pub module: usize,
    /// Placed as `~X` or `~X(s)` outside a scope: the unit box scaled
    /// alike on every axis, whatever the model's proportions.
    pub uniform: bool,
}

/// Everything one interpretation draws.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Drawing {
    pub chains: Vec<Chain>,
    /// Per chain, its [`Origin`] when the turtle knows it; shorter than
    /// `chains` when the last ones have none (or were added by others).
    pub origins: Vec<Option<Origin>>,
    pub polygons: Vec<Polygon>,
    pub shapes: Vec<Shape>,
    pub placements: Vec<Placement>,
    /// One line per constraint rule applied (docs/shapes.md).
    pub constraints: Vec<String>,
    /// How many primitives of each kind (`block`, `cylinder`, `prism`)
    /// were drawn as polygons (docs/shapes.md).
    pub primitives: std::collections::BTreeMap<String, usize>,
}

impl Drawing {
    pub fn is_empty(&self) -> bool {
        self.chains.is_empty()
            && self.polygons.is_empty()
            && self.shapes.is_empty()
            && self.placements.is_empty()
    }

    /// A deterministic text form for snapshot tests: every coordinate to
    /// three decimals (negative zero printed as zero), one record per line.
    pub fn dump(&self, symbol_name: impl Fn(SymId) -> String) -> String {
        let mut out = String::new();
        for c in &self.chains {
            let _ = write!(out, "tube colour {} :", c.colour);
            for p in &c.points {
                let _ = write!(out, " {} r{}", v(p.pos), n(p.radius));
            }
            out.push('\n');
        }
        for p in &self.polygons {
            let _ = write!(out, "polygon colour {} :", p.colour);
            for q in &p.points {
                let _ = write!(out, " {}", v(*q));
            }
            out.push('\n');
        }
        for s in &self.shapes {
            let _ = writeln!(
                out,
                "{:?} colour {} at {} normal {} r{}",
                s.kind,
                s.colour,
                v(s.centre),
                v(s.normal),
                n(s.radius)
            );
        }
        for (kind, n) in &self.primitives {
            let _ = writeln!(out, "primitives {kind}: {n}");
        }
        for c in &self.constraints {
            let _ = writeln!(out, "constraint: {c}");
        }
        for p in &self.placements {
            let m = p.transform;
            let _ = writeln!(
                out,
                "place {} colour {} at {} x {} y {} z {}",
                symbol_name(p.symbol),
                p.colour,
                v(m.w_axis.truncate()),
                v(m.x_axis.truncate()),
                v(m.y_axis.truncate()),
                v(m.z_axis.truncate())
            );
        }
        out
    }
}

fn n(x: f32) -> String {
    let s = format!("{x:.3}");
    if s == "-0.000" {
        "0.000".to_string()
    } else {
        s
    }
}

fn v(p: Vec3) -> String {
    format!("({},{},{})", n(p.x), n(p.y), n(p.z))
}
