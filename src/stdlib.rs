//! The standard library: `.lsys` files from `grammar/std/`, embedded in the
//! binary so `std:NAME` and `#include <NAME>` work on any machine.

/// A standard library grammar.
pub struct StdFile {
    /// What `std:NAME` and `#include <NAME>` call it.
    pub name: &'static str,
    pub text: &'static str,
    /// Its syntax tree, parsed when the crate was built (`build.rs`;
    /// postcard, spans without their file): see `parse::stored`.
    pub tree: &'static [u8],
}

macro_rules! std_files {
    ($($name:literal),*) => {
        &[$(StdFile {
            name: $name,
            text: include_str!(concat!("../grammar/std/", $name, ".lsys")),
            tree: include_bytes!(concat!(env!("OUT_DIR"), "/std_ast/", $name, ".ast")),
        }),*]
    };
}

/// Every standard library grammar.
pub const FILES: &[StdFile] = std_files!("toukung_middle", "toukung_side", "pailou");

/// The text of the standard library file `name` (with or without `.lsys`).
pub fn get(name: &str) -> Option<&'static str> {
    let name = name.strip_suffix(".lsys").unwrap_or(name);
    FILES.iter().find(|f| f.name == name).map(|f| f.text)
}

/// The help of an unknown library name: the name meant, if one is at
/// most two edits away (written by `spell`: `std:NAME`, `#include <NAME>`),
/// and every name.
pub fn unknown_help(name: &str, spell: impl Fn(&str) -> String) -> String {
    let name = name.strip_suffix(".lsys").unwrap_or(name);
    let all = names().join(", ");
    let closest = FILES
        .iter()
        .map(|f| (strsim::levenshtein(name, f.name), f.name))
        .filter(|&(d, _)| d <= 2)
        .min();
    match closest {
        Some((_, n)) => format!(
            "did you mean `{}`? the standard library has: {all}",
            spell(n)
        ),
        None => format!("the standard library has: {all}"),
    }
}

/// Names of all standard library files, for help texts.
pub fn names() -> Vec<&'static str> {
    FILES.iter().map(|f| f.name).collect()
}

/// `$make!(SET: NAMES)`: a table of every built-in component model in
/// `grammar/std/components/SET` (written by `scripts/make_components.py`),
/// one list of names for the four tables below.
macro_rules! for_components {
    ($make:ident!($set:literal)) => {
        $make!($set: "MAL", "MAO", "MAn", "MBP", "MCa", "MCH", "MCS", "MFB", "MIB", "ML", "MLO", "MLS", "MNo", "MP", "MPB", "MPC", "MQ", "MRO", "MSA", "MY")
    };
}

/// The OBJ texts of components `names` from set `set` (`""` or `"preview/"`).
macro_rules! obj_texts {
    ($set:literal: $($name:literal),*) => {
        &[$((
            $name,
            include_str!(concat!("../grammar/std/components/", $set, $name, ".obj")),
        )),*]
    };
}

/// (name, OBJ text) of every built-in component model: the set built at
/// the default `--detail` and above.
pub const COMPONENTS: &[(&str, &str)] = for_components!(obj_texts!(""));

/// The same components with a third of the segments on every curve, for
/// previews (`--detail 0`), from `grammar/std/components/preview/`.
pub const PREVIEW_COMPONENTS: &[(&str, &str)] = for_components!(obj_texts!("preview/"));

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
pub const DECODED: &[(&str, &[u8])] = for_components!(decoded!(""));

/// The decoded meshes of [`PREVIEW_COMPONENTS`].
pub const DECODED_PREVIEW: &[(&str, &[u8])] = for_components!(decoded!("preview/"));

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
