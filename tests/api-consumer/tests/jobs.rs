//! Whole jobs through the public API alone, as a program that builds
//! models writes them: a Pailou from a style and from a graph file, a
//! guided scene, a shape grammar with a constraint rule, and the place of
//! a mistake in a graph. Snapshots hold each job's figures (timings left
//! out: they differ from run to run).

use std::path::{Path, PathBuf};

use lsys::driver::{self, Format, GuidedJob, Job, Output, Pailou, PailouError, PailouType};
use lsys::{Grammar, Message};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn glb() -> Output {
    Output::Bytes {
        format: Format::Glb,
        picture: Default::default(),
    }
}

/// Runs `job`, keeping every warning and notice it reports; its figures
/// without timings, the notices, and the GLB's header checked.
fn figures(job: &Job) -> String {
    let mut notices = Vec::new();
    let done = driver::run(job, &mut |e| match e {
        driver::Event::Notice(n) => notices.push(n.to_string()),
        driver::Event::Warning(w) => notices.push(Message::from_diagnostic(w).to_string()),
        _ => {}
    })
    .expect("the job runs");
    let bytes = done.bytes.as_deref().expect("bytes were asked for");
    assert_eq!(&bytes[..4], b"glTF", "a GLB starts with its magic");
    assert_eq!(done.written, bytes.len() as u64);
    let mut stats = done.stats();
    stats.as_object_mut().unwrap().remove("timings_ms");
    format!(
        "{}\nproblems: {}\nnotices:\n{}",
        serde_json_pretty(&stats),
        done.problems.len(),
        notices.join("\n")
    )
}

fn serde_json_pretty(v: &impl std::fmt::Display) -> String {
    v.to_string().replace(",\"", ",\n\"")
}

#[test]
fn a_pailou_from_a_style() {
    let p = Pailou::style("2-1-1", PailouType::Ridge).unwrap();
    assert!(p.chart().contains('\n'), "the layout has a chart");
    let job = p.job(Grammar::options()).output(glb());
    insta::assert_snapshot!(figures(&job));
}

#[test]
fn a_pailou_from_a_graph_file_with_a_define() {
    let path = examples().join("pailou/fig18-4_2-1-1.toml");
    let p = Pailou::graph_file(&path, None).unwrap();
    assert!(p.unplaced().is_empty());
    let job = p.job(Grammar::options().define("NTL", 3)).output(glb());
    insta::assert_snapshot!(figures(&job));
}

#[test]
fn a_mistake_in_a_graph_has_a_code_and_a_place() {
    let text =
        "type = \"ridge\"\ncentre = \"L11\"\n\n[components]\nL11 = \"lintel\"\nX = \"dragon\"\n";
    let Err(PailouError::Graph(e)) = Pailou::graph("gate.toml", text, None) else {
        panic!("a dragon is no Pailou component");
    };
    let m = Message::from_diagnostic(e.as_ref());
    insta::assert_snapshot!(format!(
        "{:?} {:?} {:?} {:?}\n{}\nhelp: {}",
        m.code,
        m.file,
        m.line,
        m.column,
        m.message,
        m.help.unwrap_or_default()
    ));
}

#[test]
fn a_guided_scene() {
    let job = GuidedJob {
        path: examples().join("guided/links.toml"),
        options: Grammar::options(),
        guides: true,
        output: glb(),
    };
    let done = driver::run_guided(&job).expect("the scene runs");
    let bytes = done.bytes.as_deref().expect("bytes were asked for");
    assert_eq!(&bytes[..4], b"glTF");
    let mut stats = done.stats();
    stats.as_object_mut().unwrap().remove("timings_ms");
    insta::assert_snapshot!(serde_json_pretty(&stats));
}

#[test]
fn a_shape_grammar_with_a_constraint_rule() {
    let path = examples().join("shapes/wall.lsys");
    let job = Job::new(driver::Input::Path(path), "wall.lsys", Grammar::options()).output(glb());
    insta::assert_snapshot!(figures(&job));
}
