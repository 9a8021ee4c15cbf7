//! Guided procedural modeling (Beneš, Šťava, Měch, Miller 2011): a scene
//! file of closed **guides** (each hosting a grammar), oriented **links**
//! between guide edges carrying **tokens**, and **seeds** in; every seed's
//! derived string and its drawing, clipped to its guide, out.
//!
//! ```text
//! scene.rs    TOML text -> SceneSpec (located diagnostics lsys::guided::*)
//! load.rs     SceneSpec + grammar files -> Loaded (grammars compiled)
//! geometry.rs distances, hits, inside tests in the drawing plane
//! grid.rs     one pass's elements of a guide -> the few a query looks at
//! tokens.rs   free -> reserved -> used
//! queries.rs  ?DL ?DG ?DA ?NL ?NG ?NA ?X answered (an Environment)
//! run.rs      all seeds in lockstep, messages -> new seeds; local update
//! build.rs    an Outcome -> one Scene (the clipped drawings, the overlay)
//! draw.rs     placing, clipping, the guide/link overlay
//! document.rs a scene as the studio edits it: JSON <-> TOML text
//! springs.rs  mass-spring editing: a dragged vertex -> every guide relaxed
//! ```
//!
//! See docs/guided.md for the file format, the query layout and the token
//! rules.

pub mod build;
pub mod document;
pub mod draw;
pub mod geometry;
pub mod grid;
pub mod load;
pub mod queries;
pub mod run;
pub mod scene;
pub mod springs;
pub mod tokens;

pub use load::{load_file, load_text, load_text_within, Loaded};
pub use run::{run, update, Origin, Outcome, SeedRun};
pub use scene::{SceneError, SceneSpec};
