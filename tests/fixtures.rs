//! One test binary, one insta glob per stage. Each fixture is an `.lsys`
//! file under `tests/fixtures/<stage>/{ok,err}/`; its snapshot records
//! what that stage makes of it. `ok` fixtures must compile without errors
//! and `err` fixtures must fail, so a fixture cannot silently change sides.

use std::path::Path;

use lsys::internals::derive::{self, DeriveOptions, NumberFormat};
use lsys::internals::load::{Input, Options};
use lsys::internals::pipeline;
use lsys::internals::source::{Origin, SourceFile};

/// The fixture's path relative to the package, so snapshots do not depend
/// on where the repository is checked out.
fn rel(path: &Path) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    path.strip_prefix(root)
        .unwrap_or(path)
        .to_string_lossy()
        .replace('\\', "/")
}

fn expect_ok(path: &Path) -> bool {
    let p = rel(path);
    assert!(
        p.contains("/ok/") || p.contains("/err/"),
        "fixture {p} must live in an ok/ or err/ folder"
    );
    p.contains("/ok/")
}

/// `-D NAME=VALUE` overrides a fixture asks for on a `// -D NAME=VALUE` line.
fn fixture_defines(text: &str) -> Vec<(String, String)> {
    text.lines()
        .filter_map(|l| l.trim().strip_prefix("// -D "))
        .filter_map(|d| d.split_once('='))
        .map(|(n, v)| (n.trim().to_string(), v.trim().to_string()))
        .collect()
}

/// A limit a fixture sets on a `// --max-NAME N` line (so that a fixture
/// can hit a limit without being huge), e.g. `// --max-triangles 100`.
fn fixture_limit(text: &str, option: &str) -> Option<usize> {
    text.lines()
        .filter_map(|l| l.trim().strip_prefix("// "))
        .filter_map(|l| l.strip_prefix(option))
        .find_map(|v| v.trim().parse().ok())
}

/// Reads a fixture, lossily when it is not UTF-8 (as lsys reads files).
fn read_fixture(path: &Path) -> String {
    String::from_utf8_lossy(&std::fs::read(path).unwrap()).into_owned()
}

/// Compiles a fixture: the compilation, or every diagnostic rendered.
fn compile(path: &Path) -> Result<pipeline::Compilation, String> {
    let text = read_fixture(path);
    let mut opts = Options {
        defines: fixture_defines(&text),
        ..Options::default()
    };
    if let Some(n) = fixture_limit(&text, "--max-include-depth") {
        opts.max_include_depth = n;
    }
    if let Some(n) = fixture_limit(&text, "--max-nesting") {
        opts.parse.max_nesting = n;
    }
    if let Some(n) = fixture_limit(&text, "--max-operators") {
        opts.parse.max_operators = n;
    }
    match pipeline::compile(&Input::Path(rel(path).into()), &opts) {
        Ok(c) => Ok(c),
        Err(d) => Err(d.render_plain()),
    }
}

/// What a stage makes of a fixture: `ok` applied to the compilation of an
/// `ok/` fixture, or the diagnostics of an `err/` one.
fn outcome(path: &Path, ok: impl FnOnce(&pipeline::Compilation) -> String) -> String {
    outcome_or_runtime(path, |c| Ok::<_, lsys::internals::build::BuildError>(ok(c)))
}

fn warnings(c: &pipeline::Compilation) -> String {
    c.warnings
        .iter()
        .map(|d| lsys::internals::diag::render_plain(d.as_ref()))
        .collect()
}

#[test]
fn parse() {
    insta::glob!("fixtures/parse/*/*.lsys", |path| {
        let name = rel(path);
        let text = read_fixture(path);
        let limits = lsys::internals::parse::Limits {
            max_nesting: fixture_limit(&text, "--max-nesting")
                .unwrap_or(lsys::internals::parse::MAX_NESTING),
            max_operators: fixture_limit(&text, "--max-operators")
                .unwrap_or(lsys::internals::parse::MAX_OPERATORS),
        };
        let file = SourceFile::new(name.clone(), Origin::Disk(name.clone().into()), text);
        let (ast, errors) = lsys::internals::parse::parse_limited(0, &file, limits);
        assert_eq!(
            expect_ok(path),
            errors.is_empty(),
            "{name}: ok/ fixtures parse, err/ ones do not"
        );
        let mut out = ast.dump();
        for e in &errors {
            out.push_str(&lsys::internals::diag::render_plain(e));
        }
        insta::assert_snapshot!(out);
    });
}

#[test]
fn resolve() {
    insta::glob!("fixtures/resolve/*/*.lsys", |path| {
        let out = outcome(path, |c| {
            let p = &c.program;
            let mut out = warnings(c);
            out.push_str(&format!(
                    "symbols: {}\naxiom: {}\nderivation length: {}\nproductions: {} main, {} decomposition, {} homomorphism\n",
                    p.symbols.list.iter().map(|s| format!("{}:{:?}", s.name, s.kind)).collect::<Vec<_>>().join(" "),
                    p.axiom.iter().map(|m| p.symbols.name(m.sym)).collect::<Vec<_>>().join(" "),
                    p.derivation_length,
                    p.productions.len(),
                    p.decomposition.len(),
                    p.homomorphism.len(),
                ));
            for d in &p.defines {
                out.push_str(&format!(
                    "define {} = {:?}{}\n",
                    d.name,
                    d.value,
                    if d.overridden { " (overridden)" } else { "" }
                ));
            }
            out
        });
        insta::assert_snapshot!(out);
    });
}

#[test]
fn bytecode() {
    insta::glob!("fixtures/bytecode/*/*.lsys", |path| {
        let out = outcome(path, |c| {
            lsys::internals::bytecode::disasm(&c.program, &c.compiled)
        });
        insta::assert_snapshot!(out);
    });
}

/// Derives a fixture, printing every step (and the homomorphism of the
/// last one when the grammar has one); `err` fixtures fail at run time.
#[test]
fn derive() {
    insta::glob!("fixtures/derive/*/*.lsys", |path| {
        let c = compile(path).unwrap_or_else(|d| panic!("{}: does not compile:\n{d}", rel(path)));
        let (p, code) = (&c.program, &c.compiled);
        let text = read_fixture(path);
        let opts = DeriveOptions {
            max_modules: fixture_limit(&text, "--max-modules").unwrap_or(10_000),
            max_params: fixture_limit(&text, "--max-params")
                .unwrap_or(DeriveOptions::default().max_params),
            ..DeriveOptions::default()
        };
        // Parameters as the dialect stores them (f32 in cpfg's).
        let fmt = NumberFormat::for_program(p);
        let mut out = warnings(&c);
        let mut run = || -> Result<derive::Derivation, derive::DeriveError> {
            let steps = p.derivation_length;
            let mut d = lsys::internals::simulation::Simulation::new(p, code, opts.clone(), steps)?;
            out.push_str(&format!(
                "0: {}\n",
                d.current().display_with(&p.symbols, fmt)
            ));
            for _ in 0..p.derivation_length {
                d.step()?;
                out.push_str(&format!(
                    "{}: {}\n",
                    d.step_number(),
                    d.current().display_with(&p.symbols, fmt)
                ));
            }
            d.finish()?;
            Ok(d.into_derivation())
        };
        match run() {
            Ok(d) => {
                assert!(expect_ok(path), "{}: expected a runtime error", rel(path));
                for w in d.warnings() {
                    out.push_str(&lsys::internals::diag::render_plain(w));
                }
                if !p.homomorphism.is_empty() {
                    let h = d.homomorphism().unwrap();
                    out.push_str(&format!(
                        "homomorphism: {}\n",
                        h.modules.display_with(&p.symbols, fmt)
                    ));
                    for w in &h.warnings {
                        out.push_str(&lsys::internals::diag::render_plain(w));
                    }
                }
            }
            Err(e) => {
                assert!(
                    !expect_ok(path),
                    "{}: unexpected runtime error:\n{}",
                    rel(path),
                    lsys::internals::diag::render_plain(&e)
                );
                out.push_str(&lsys::internals::diag::render_plain(&e));
            }
        }
        insta::assert_snapshot!(out);
    });
}

/// Builds a fixture (derive, homomorphism, turtle, meshes) and prints what
/// the turtle drew and the scene it became; `err` fixtures fail to build.
/// Components come from `components/` beside the fixture.
#[test]
fn turtle() {
    insta::glob!("fixtures/turtle/*/*.lsys", |path| {
        let text = read_fixture(path);
        let out = outcome_or_runtime(path, |c| {
            let opts = lsys::internals::build::BuildOptions {
                components: lsys::internals::mesh::ComponentSearch {
                    grammar_dir: Some(Path::new(&rel(path)).parent().unwrap().to_path_buf()),
                    dirs: Vec::new(),
                    ..Default::default()
                },
                mesh: lsys::internals::mesh::MeshOptions {
                    max_triangles: fixture_limit(&text, "--max-triangles")
                        .unwrap_or(lsys::internals::mesh::MeshOptions::default().max_triangles),
                    ..Default::default()
                },
                ..Default::default()
            };
            lsys::internals::build::build(c, &opts).map(|b| {
                let mut out = warnings(c);
                out.push_str(&b.drawing.dump(|s| c.program.symbols.name(s).to_string()));
                out.push_str("--\n");
                out.push_str(&b.scene.summary());
                out
            })
        });
        insta::assert_snapshot!(out);
    });
}

/// Every example builds; its snapshot records what the turtle drew (record
/// counts, and every record for small drawings) and the scene's summary.
#[test]
fn examples_build() {
    insta::glob!(
        concat!(env!("CARGO_MANIFEST_DIR"), "/examples"),
        "**/*.lsys",
        |path| {
            // Guided grammars run only inside their scenes (tests/guided.rs).
            if path.components().any(|c| c.as_os_str() == "guided") {
                return;
            }
            // A library of rules, built through the examples that include
            // it (examples/shapes/hall_parts.lsys).
            if path.to_string_lossy().ends_with("_parts.lsys") {
                return;
            }
            let c =
                compile(path).unwrap_or_else(|d| panic!("{}: does not compile:\n{d}", rel(path)));
            let opts = lsys::internals::build::BuildOptions {
                components: lsys::internals::mesh::ComponentSearch {
                    grammar_dir: Some(path.parent().unwrap().to_path_buf()),
                    dirs: Vec::new(),
                    ..Default::default()
                },
                ..Default::default()
            };
            let b = lsys::internals::build::build(&c, &opts).unwrap_or_else(|e| {
                panic!("{}: {}", rel(path), lsys::internals::diag::render_plain(&e))
            });
            let d = &b.drawing;
            let mut out = format!(
                "modules {}: tubes {} (points {}), polygons {}, shapes {}, placements {}\n",
                b.modules,
                d.chains.len(),
                d.chains.iter().map(|c| c.points.len()).sum::<usize>(),
                d.polygons.len(),
                d.shapes.len(),
                d.placements.len()
            );
            if d.chains.len() + d.polygons.len() + d.shapes.len() + d.placements.len() <= 40 {
                out.push_str(&d.dump(|s| c.program.symbols.name(s).to_string()));
            }
            out.push_str("--\n");
            out.push_str(&b.scene.summary());
            insta::assert_snapshot!(out);
        }
    );
}

/// Like [`outcome`], but `ok` may also fail at run time: `ok/` fixtures
/// must succeed and `err/` fixtures must fail, at compile or run time.
fn outcome_or_runtime<E: miette::Diagnostic>(
    path: &Path,
    run: impl FnOnce(&pipeline::Compilation) -> Result<String, E>,
) -> String {
    match compile(path) {
        Ok(c) => {
            let mut out = String::new();
            match run(&c) {
                Ok(s) => {
                    assert!(expect_ok(path), "{}: expected an error", rel(path));
                    out.push_str(&s);
                }
                Err(e) => {
                    let text = lsys::internals::diag::render_plain(&e);
                    assert!(!expect_ok(path), "{}: unexpected error:\n{text}", rel(path));
                    out.push_str(&text);
                }
            }
            out
        }
        Err(diags) => {
            assert!(
                !expect_ok(path),
                "{}: expected no errors, got:\n{diags}",
                rel(path)
            );
            diags
        }
    }
}

/// The classic systems of ABOP chapter 1 derive to the strings the book
/// gives, as computed independently by `scripts/abop_oracle.py`.
#[test]
fn abop_examples() {
    insta::glob!(
        concat!(env!("CARGO_MANIFEST_DIR"), "/examples/abop"),
        "*.lsys",
        |path| {
            let c =
                compile(path).unwrap_or_else(|d| panic!("{}: does not compile:\n{d}", rel(path)));
            let s = lsys::internals::simulation::derive(
                &c.program,
                &c.compiled,
                DeriveOptions::default(),
                c.program.derivation_length,
            )
            .unwrap()
            .display(&c.program.symbols);
            let stem = path.file_stem().unwrap().to_string_lossy();
            let oracle = Path::new(env!("CARGO_MANIFEST_DIR"))
                .join(format!("tests/abop_expected/{stem}.txt"));
            let expected = std::fs::read_to_string(&oracle)
                .unwrap_or_else(|e| panic!("{}: {e}", oracle.display()));
            assert_eq!(s, expected.trim_end(), "{stem} differs from the oracle");
            insta::assert_snapshot!(s);
        }
    );
}
