//! How OBJ component models are read (tobj's options): one definition for
//! the program (`components::parse_obj`) and for `build.rs`, which reads
//! the built-in models at compile time (it includes this file), so both
//! read the very same meshes.

/// One index per vertex (positions and normals together), triangles only.
pub fn obj_options() -> tobj::LoadOptions {
    tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    }
}
