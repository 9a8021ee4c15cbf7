//! The standard library: `.lsys` files from `grammar/std/`, embedded in the
//! binary so `std:NAME` and `#include <NAME>` work on any machine.

/// (name, source text) of every standard library file.
pub const FILES: &[(&str, &str)] = &[
    (
        "toukung_middle",
        include_str!("../grammar/std/toukung_middle.lsys"),
    ),
    (
        "toukung_side",
        include_str!("../grammar/std/toukung_side.lsys"),
    ),
    ("pailou", include_str!("../grammar/std/pailou.lsys")),
];

/// (name, syntax tree) of every standard library file, parsed when the
/// crate was built (`build.rs`; postcard, spans without their file): see
/// `parse::stored`.
pub const PARSED: &[(&str, &[u8])] = &[
    (
        "toukung_middle",
        include_bytes!(concat!(env!("OUT_DIR"), "/std_ast/toukung_middle.ast")),
    ),
    (
        "toukung_side",
        include_bytes!(concat!(env!("OUT_DIR"), "/std_ast/toukung_side.ast")),
    ),
    (
        "pailou",
        include_bytes!(concat!(env!("OUT_DIR"), "/std_ast/pailou.ast")),
    ),
];

/// The text of the standard library file `name` (with or without `.lsys`).
pub fn get(name: &str) -> Option<&'static str> {
    let name = name.strip_suffix(".lsys").unwrap_or(name);
    FILES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// Names of all standard library files, for help texts.
pub fn names() -> Vec<&'static str> {
    FILES.iter().map(|(n, _)| *n).collect()
}

/// (name, OBJ text) of every built-in component model, from
/// `grammar/std/components/` (written by `scripts/make_components.py`):
/// the set built at the default `--detail` and above.
pub const COMPONENTS: &[(&str, &str)] = &[
    ("MAL", include_str!("../grammar/std/components/MAL.obj")),
    ("MAO", include_str!("../grammar/std/components/MAO.obj")),
    ("MAn", include_str!("../grammar/std/components/MAn.obj")),
    ("MBP", include_str!("../grammar/std/components/MBP.obj")),
    ("MCa", include_str!("../grammar/std/components/MCa.obj")),
    ("MFB", include_str!("../grammar/std/components/MFB.obj")),
    ("MIB", include_str!("../grammar/std/components/MIB.obj")),
    ("ML", include_str!("../grammar/std/components/ML.obj")),
    ("MNo", include_str!("../grammar/std/components/MNo.obj")),
    ("MP", include_str!("../grammar/std/components/MP.obj")),
    ("MPB", include_str!("../grammar/std/components/MPB.obj")),
    ("MQ", include_str!("../grammar/std/components/MQ.obj")),
    ("MY", include_str!("../grammar/std/components/MY.obj")),
];

/// The same components with a third of the segments on every curve, for
/// previews (`--detail 0`), from `grammar/std/components/preview/`.
pub const PREVIEW_COMPONENTS: &[(&str, &str)] = &[
    (
        "MAL",
        include_str!("../grammar/std/components/preview/MAL.obj"),
    ),
    (
        "MAO",
        include_str!("../grammar/std/components/preview/MAO.obj"),
    ),
    (
        "MAn",
        include_str!("../grammar/std/components/preview/MAn.obj"),
    ),
    (
        "MBP",
        include_str!("../grammar/std/components/preview/MBP.obj"),
    ),
    (
        "MCa",
        include_str!("../grammar/std/components/preview/MCa.obj"),
    ),
    (
        "MFB",
        include_str!("../grammar/std/components/preview/MFB.obj"),
    ),
    (
        "MIB",
        include_str!("../grammar/std/components/preview/MIB.obj"),
    ),
    (
        "ML",
        include_str!("../grammar/std/components/preview/ML.obj"),
    ),
    (
        "MNo",
        include_str!("../grammar/std/components/preview/MNo.obj"),
    ),
    (
        "MP",
        include_str!("../grammar/std/components/preview/MP.obj"),
    ),
    (
        "MPB",
        include_str!("../grammar/std/components/preview/MPB.obj"),
    ),
    (
        "MQ",
        include_str!("../grammar/std/components/preview/MQ.obj"),
    ),
    (
        "MY",
        include_str!("../grammar/std/components/preview/MY.obj"),
    ),
];

/// The OBJ text of the built-in component `name` (without `~`) at the
/// default level of detail.
pub fn component(name: &str) -> Option<&'static str> {
    component_at(name, 1)
}

/// The OBJ text of the built-in component `name` at level of `detail`
/// (0: the preview set).
pub fn component_at(name: &str, detail: u8) -> Option<&'static str> {
    let set = if detail == 0 {
        PREVIEW_COMPONENTS
    } else {
        COMPONENTS
    };
    set.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The meshes of built-in components `names` from set `set` (`""` or
/// `"preview/"`), as build.rs decoded them from the OBJ models.
macro_rules! decoded {
    ($set:literal: $($name:literal),*) => {
        &[$((
            $name,
            include_bytes!(concat!(env!("OUT_DIR"), "/components/", $set, $name, ".mesh"))
                as &[u8],
        )),*]
    };
}

/// (name, decoded mesh) of every built-in component model: the meshes of
/// [`COMPONENTS`] as tobj reads them, decoded at build time (build.rs) so
/// that a build does not parse OBJ text (`mesh::components::built_in`).
pub const DECODED: &[(&str, &[u8])] = decoded!("": "MAL", "MAO", "MAn", "MBP", "MCa", "MFB", "MIB", "ML", "MNo", "MP", "MPB", "MQ", "MY");

/// The decoded meshes of [`PREVIEW_COMPONENTS`].
pub const DECODED_PREVIEW: &[(&str, &[u8])] = decoded!("preview/": "MAL", "MAO", "MAn", "MBP", "MCa", "MFB", "MIB", "ML", "MNo", "MP", "MPB", "MQ", "MY");

/// The decoded mesh of the built-in component `name` at level of `detail`
/// (0: the preview set).
pub fn decoded_at(name: &str, detail: u8) -> Option<&'static [u8]> {
    let set = if detail == 0 {
        DECODED_PREVIEW
    } else {
        DECODED
    };
    set.iter().find(|(n, _)| *n == name).map(|(_, m)| *m)
}

/// Components that are standard library grammars: `~TM(s)` places the
/// middle Toukung, `~TS(s)` the side one (paper, Fig 10), each derived once.
pub const GRAMMAR_COMPONENTS: &[(&str, &str)] = &[("TM", "toukung_middle"), ("TS", "toukung_side")];

/// The standard library grammar that component `name` stands for.
pub fn grammar_component(name: &str) -> Option<&'static str> {
    GRAMMAR_COMPONENTS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, g)| *g)
}
