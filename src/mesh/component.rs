//! Components: one distinct model, stored once however often it is placed.
//! Input: parts read from an OBJ model, or a small scene of placed smaller
//! components (a grammar component, a tiled roof); output: a [`Component`]
//! whose flattened parts are built on first use.
//!
//! Why on first use: a Pailou places 42 Toukungs of two kinds and 15 roofs.
//! The glTF writer places their smaller parts through a node hierarchy
//! ([`Nested`]) and never reads the flattened meshes, which were 2 M
//! vertices merged, transformed and normalised on every build (about a
//! third of the Pailou's first touches of fresh memory). The OBJ writer,
//! the renderer and `--stats`' bounds still read them, and get exactly the
//! meshes that were built before.

use std::fmt;
use std::sync::{Arc, OnceLock};

use glam::Mat4;

use super::scene::{Instance, Part};

/// A distinct component mesh, stored once however often it is placed. Its
/// geometry is normalised to the unit box centred at the origin: width x,
/// height y, depth z, front facing -z.
#[derive(Clone, Debug)]
pub struct Component {
    /// The symbol that places it, e.g. `MCa` for `~MCa`.
    pub name: String,
    /// Where it came from: a file path or `built-in`.
    pub origin: String,
    /// The same geometry as [`Component::parts`], kept as placements of
    /// smaller components, when it was built from them (a grammar
    /// component, a tiled roof). Everything that draws or measures reads
    /// `parts()`; exporters that keep a node hierarchy (glTF) write this
    /// instead, so each smaller component is stored once in the file.
    pub nested: Option<Box<Nested>>,
    /// The model's size before it was normalised to the unit box (width,
    /// height, depth), when it has proportions of its own: an OBJ model, a
    /// grammar component. `None` for meshes made to be stretched (roofs,
    /// the unit cylinder, cpfg surfaces). Read to warn when `~X` or `~X(s)`
    /// draws an elongated model as a cube.
    pub modelled: Option<glam::Vec3>,
    parts: OnceLock<Vec<Part>>,
    /// Builds `parts` when they were left for later.
    later: Option<Later>,
}

/// A component as a small scene of its own (see [`Component::nested`]).
/// Material indices are the outer scene's.
#[derive(Clone, Debug)]
pub struct Nested {
    /// Inner space -> the component's unit box (its normalisation).
    pub frame: Mat4,
    /// Geometry drawn directly, in inner space, each part with its material.
    pub parts: Vec<Part>,
    pub components: Vec<Component>,
    /// Placements of `components`, in inner space.
    pub instances: Vec<Instance>,
    /// Whether parts without a material of their own take the colour of
    /// the outer placement (a roof's tiles) instead of the inner
    /// placement's (a grammar's own colours).
    pub placement_colour: bool,
}

/// What a component built later knows of its parts before they exist.
#[derive(Clone)]
pub struct Later {
    pub vertices: usize,
    pub triangles: usize,
    /// Whether some part will take the placement's colour.
    pub placement_colour: bool,
    pub build: Flatten,
}

/// Builds the flattened, normalised parts from the component's nested
/// scene (`None` only if the component has none).
pub type Flatten = Arc<dyn Fn(Option<&Nested>) -> Vec<Part> + Send + Sync>;

impl fmt::Debug for Later {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Later")
            .field("vertices", &self.vertices)
            .field("triangles", &self.triangles)
            .field("placement_colour", &self.placement_colour)
            .finish_non_exhaustive()
    }
}

impl Component {
    /// A component of parts already built (an OBJ model, a procedural mesh).
    pub fn new(name: impl Into<String>, origin: impl Into<String>, parts: Vec<Part>) -> Self {
        Component {
            name: name.into(),
            origin: origin.into(),
            nested: None,
            modelled: None,
            parts: OnceLock::from(parts),
            later: None,
        }
    }

    /// The same, with the model's size before normalisation.
    pub fn with_modelled(mut self, size: glam::Vec3) -> Self {
        self.modelled = Some(size);
        self
    }

    /// A component kept as `nested`, whose flattened parts `later` builds
    /// the first time something reads them.
    pub fn built_later(
        name: impl Into<String>,
        origin: impl Into<String>,
        nested: Nested,
        later: Later,
    ) -> Self {
        Component {
            name: name.into(),
            origin: origin.into(),
            nested: Some(Box::new(nested)),
            modelled: None,
            parts: OnceLock::new(),
            later: Some(later),
        }
    }

    /// The component's geometry, one part per material, in its unit box
    /// (built now if it was left for later).
    pub fn parts(&self) -> &[Part] {
        self.parts.get_or_init(|| match &self.later {
            Some(later) => (later.build)(self.nested.as_deref()),
            None => Vec::new(),
        })
    }

    /// The parts to change in place (built now if they were left for later).
    pub fn parts_mut(&mut self) -> &mut Vec<Part> {
        self.parts();
        // A component changed in place is no longer what `later` builds.
        self.later = None;
        self.parts.get_mut().expect("built above")
    }

    /// Whether the flattened parts exist yet (tests: what a build left
    /// for later).
    pub fn parts_built(&self) -> bool {
        self.parts.get().is_some()
    }

    pub fn vertex_count(&self) -> usize {
        match (&self.later, self.parts.get()) {
            (Some(later), None) => later.vertices,
            _ => self.parts().iter().map(|p| p.mesh.vertex_count()).sum(),
        }
    }

    pub fn triangle_count(&self) -> usize {
        match (&self.later, self.parts.get()) {
            (Some(later), None) => later.triangles,
            _ => self.parts().iter().map(|p| p.mesh.triangle_count()).sum(),
        }
    }

    /// True when some part takes the colour of the placement.
    pub fn uses_placement_colour(&self) -> bool {
        match (&self.later, self.parts.get()) {
            (Some(later), None) => later.placement_colour,
            _ => self.parts().iter().any(|p| p.material.is_none()),
        }
    }
}
