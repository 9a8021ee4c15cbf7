//! Build script: the built-in component models (`grammar/std/components/`
//! and its `preview/` set, OBJ text) -> their meshes as tobj reads them,
//! in a compact binary form in `OUT_DIR` (`components/NAME.mesh`,
//! `components/preview/NAME.mesh`), embedded by `src/stdlib.rs`.
//!
//! Why: reading the OBJ text with tobj took about a third of a Pailou
//! build's instructions (the Pailou and each Toukung it places read their
//! models again). The meshes are read here with the same tobj and the same
//! options as `mesh::components::parse_obj` (`src/mesh/obj_options.rs`,
//! included), so the program gets the very same numbers and only decodes
//! them.
//!
//! Format (little-endian): model count (u32); per model: positions
//! (u32 count, then f32s), normals (u32 count, then f32s), indices (u32
//! count, then u32s). Built-in models have no materials (no `.mtl` is
//! read for them), so none is stored.

use std::io::BufReader;
use std::path::Path;

#[path = "src/mesh/obj_options.rs"]
mod obj_options;

// The program's own parser, for the standard library's grammars (see
// `std_syntax_trees`). Not all of it is used here.
#[allow(dead_code)]
#[path = "src/source.rs"]
mod source;

#[allow(dead_code, unused_imports)]
#[path = "src/parse/mod.rs"]
mod parse;

/// What the parser asks of the standard library: here, where the trees
/// are made, there are none to read, so every grammar is parsed.
mod stdlib {
    #[allow(dead_code)] // the parser reads a library file's text and tree
    pub struct StdFile {
        pub name: &'static str,
        pub text: &'static str,
        pub tree: &'static [u8],
    }
    pub const FILES: &[StdFile] = &[];
}

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    std_syntax_trees(Path::new(&out));
    studio_page(Path::new(&out));
    println!("cargo:rerun-if-changed=src/mesh/obj_options.rs");
    for set in ["", "preview"] {
        let src = Path::new("grammar/std/components").join(set);
        println!("cargo:rerun-if-changed={}", src.display());
        let dst = Path::new(&out).join("components").join(set);
        std::fs::create_dir_all(&dst).expect("creates the output folder");
        for path in files(&src, "obj") {
            let text = std::fs::read(&path).expect("reads a component model");
            let stem = path.file_stem().expect("a file name");
            let bytes = encode(&text, &path);
            std::fs::write(dst.join(stem).with_extension("mesh"), bytes)
                .expect("writes a decoded component");
        }
    }
}

/// The meshes of OBJ `text`, read as `parse_obj` reads a built-in model.
fn encode(text: &[u8], path: &Path) -> Vec<u8> {
    let opts = obj_options::obj_options();
    // A built-in model has no folder to read a `.mtl` from.
    let (models, _) = tobj::load_obj_buf(&mut BufReader::new(text), &opts, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut out = Vec::new();
    let count = |out: &mut Vec<u8>, n: usize| {
        out.extend_from_slice(&u32::try_from(n).expect("fits u32").to_le_bytes())
    };
    count(&mut out, models.len());
    for m in &models {
        let m = &m.mesh;
        for floats in [&m.positions, &m.normals] {
            count(&mut out, floats.len());
            for f in floats.iter() {
                out.extend_from_slice(&f.to_le_bytes());
            }
        }
        count(&mut out, m.indices.len());
        for i in &m.indices {
            out.extend_from_slice(&i.to_le_bytes());
        }
    }
    out
}

/// The standard library's grammars (`grammar/std/*.lsys`) -> their syntax
/// trees, parsed by the program's parser and written with postcard to
/// `OUT_DIR/std_ast/NAME.ast`, embedded by `src/stdlib.rs`: a run reads
/// the tree of a standard library file instead of parsing it (see
/// `parse::stored`). A library grammar that does not parse cleanly stops
/// the build with its diagnostics (`parse::tree_to_store`).
fn std_syntax_trees(out: &Path) {
    // The folder too: a library file added to it is an input.
    for input in [
        "grammar/lsys.pest",
        "grammar/std",
        "src/source.rs",
        "src/parse",
    ] {
        println!("cargo:rerun-if-changed={input}");
    }
    let dst = out.join("std_ast");
    std::fs::create_dir_all(&dst).expect("creates the output folder");
    for path in files(Path::new("grammar/std"), "lsys") {
        let text = std::fs::read_to_string(&path).expect("reads a library grammar");
        let stem = path.file_stem().expect("a file name").to_string_lossy();
        let file = source::SourceFile::new(
            format!("std:{stem}"),
            source::Origin::Std(stem.to_string()),
            text,
        );
        let tree = parse::tree_to_store(&file).unwrap_or_else(|errors| {
            let all: Vec<String> = errors.iter().map(|e| format!("{e:?}")).collect();
            panic!(
                "{} does not parse cleanly:\n{}",
                path.display(),
                all.join("\n")
            )
        });
        let bytes = postcard::to_allocvec(&tree).expect("serializes a syntax tree");
        std::fs::write(dst.join(stem.as_ref()).with_extension("ast"), bytes)
            .expect("writes a syntax tree");
    }
}

/// The files of folder `dir` with extension `ext`, sorted; each one is an
/// input of the build.
fn files(dir: &Path, ext: &str) -> Vec<std::path::PathBuf> {
    let mut found: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("lists a folder").path())
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    found.sort();
    for path in &found {
        println!("cargo:rerun-if-changed={}", path.display());
    }
    found
}

/// The studio's built front end (`web/studio/dist`, made by `npm run
/// build`), embedded when it exists at build time, so that an installed
/// binary serves its page from anywhere; without it the server's own page
/// says how to build it. Writes `OUT_DIR/studio_page.rs`: `PAGE`, each
/// file's path in `dist` and its bytes.
fn studio_page(out: &Path) {
    // The folder around it: `dist` may not exist yet, and a path that
    // does not exist makes cargo run this script on every build.
    println!("cargo:rerun-if-changed=web/studio");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("web/studio/dist");
    let mut files = Vec::new();
    if std::env::var_os("CARGO_FEATURE_STUDIO").is_some() && root.join("index.html").is_file() {
        collect(&root, &root, &mut files);
    }
    files.sort();
    let mut code = String::from("pub static PAGE: &[(&str, &[u8])] = &[\n");
    for (rel, full) in &files {
        code += &format!("    ({rel:?}, include_bytes!({full:?})),\n");
    }
    code += "];\n";
    std::fs::write(out.join("studio_page.rs"), code).expect("OUT_DIR is writable");
}

fn collect(root: &Path, dir: &Path, files: &mut Vec<(String, String)>) {
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let path = e.path();
        if path.is_dir() {
            collect(root, &path, files);
        } else if let Ok(rel) = path.strip_prefix(root) {
            let rel = rel.to_string_lossy().replace('\\', "/");
            files.push((rel, path.to_string_lossy().into_owned()));
        }
    }
}
