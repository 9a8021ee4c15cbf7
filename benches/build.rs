//! Source to `.glb` (issue 6, W3, T and P): derive + turtle + mesh, then
//! GLB assembly and writing the file, end to end, through the same atomic
//! streaming writer as `lsys build`; plus the meshing stage alone for W3
//! (modules of the derived string per second), and (issue 19) a forest of
//! ten W2 trees (10.5 M modules) to `.glb` and to `.obj`; and (issue 36)
//! guided scenes of many seeds.

mod common;

use divan::counter::ItemsCount;
use divan::{black_box, Bencher};
use lsys::internals::build::{self, BuildOptions};
use lsys::internals::export::output::{write_scene, Format};
use lsys::internals::export::render::RenderOptions;
use lsys::internals::load::Input;
use lsys::internals::pailou::{self, PailouType};
use lsys::internals::pipeline::Compilation;

fn main() {
    divan::main();
}

fn opts() -> BuildOptions {
    BuildOptions {
        derive: common::big(),
        ..BuildOptions::default()
    }
}

/// Build `c` and write it to `name` (its extension names the format) in
/// `dir` as `lsys build` does; the bytes written.
fn to_file(c: &Compilation, dir: &std::path::Path, name: &str) -> u64 {
    let built = build::build(c, &opts()).expect("builds");
    let out = dir.join(name);
    let format = Format::of(&out).expect("a model format");
    write_scene(&built.scene, &out, format, &RenderOptions::default()).expect("writes")
}

fn to_glb_file(c: &Compilation, dir: &std::path::Path) -> u64 {
    to_file(c, dir, "out.glb")
}

fn w3(bencher: Bencher, c: Compilation) {
    let dir = tempfile::tempdir().expect("temp dir");
    let n = build::build(&c, &opts()).expect("builds").modules;
    bencher
        .counter(ItemsCount::new(n))
        .bench_local(|| black_box(to_glb_file(&c, dir.path())));
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn w3_w1_glb(bencher: Bencher) {
    w3(bencher, common::w1());
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn w3_w2_glb(bencher: Bencher) {
    w3(bencher, common::w2(18));
}

/// The forest (ten W2 trees, 10.5 M modules) to `.glb` and `.obj`.
#[divan::bench(args = ["glb", "obj"], sample_count = 3, sample_size = 1)]
fn forest(bencher: Bencher, ext: &str) {
    let c = common::grammar("forest.lsys", &[]);
    let dir = tempfile::tempdir().expect("temp dir");
    let n = build::build(&c, &opts()).expect("builds").modules;
    let name = format!("forest.{ext}");
    bencher
        .counter(ItemsCount::new(n))
        .bench_local(|| black_box(to_file(&c, dir.path(), &name)));
    // Untimed: the samples' files (0.5-2 GB each) are still being written
    // back when the samples end, and the benchmarks after this one (a
    // Toukung build, 1.3 ms, replaces its file and waits on that disk)
    // had samples of 50 ms, a mean ten times their median. `sync` waits
    // for the disk to be idle again.
    drop(dir);
    let synced = std::process::Command::new("sync").status();
    assert!(synced.is_ok_and(|s| s.success()), "sync runs");
}

/// Meshing alone (tubes), modules of the string per second.
#[divan::bench(sample_count = 5, sample_size = 1)]
fn w3_w2_mesh_only(bencher: Bencher) {
    let c = common::w2(18);
    let built = build::build(&c, &opts()).expect("builds");
    let palette = lsys::internals::mesh::Palette::new(&c.program.turtle.palette);
    let o = opts();
    bencher
        .counter(ItemsCount::new(built.modules))
        .bench_local(|| {
            black_box(
                lsys::internals::mesh::assemble_scene(
                    &c.program,
                    &built.drawing,
                    &palette,
                    &o.components,
                    &o.mesh,
                    &mut lsys::internals::mesh::NoGrammars,
                )
                .expect("meshes"),
            )
        });
}

/// T: the Toukung side view with NTL = 18, source (compiled each time)
/// to `.glb`.
#[divan::bench(sample_count = 20)]
fn t_toukung_side_glb(bencher: Bencher) {
    let dir = tempfile::tempdir().expect("temp dir");
    bencher.bench_local(|| {
        let c = common::compile(Input::Std("toukung_side".into()), &[("NTL", "18")]);
        black_box(to_glb_file(&c, dir.path()))
    });
}

/// P: the 6-5-15 Pailou, style to generated grammar to `.glb`.
#[divan::bench(sample_count = 20)]
fn p_pailou_6_5_15_glb(bencher: Bencher) {
    let dir = tempfile::tempdir().expect("temp dir");
    bencher.bench_local(|| {
        let layout = pailou::style_layout("6-5-15", PailouType::Ridge).expect("style");
        let input = pailou::input(&layout, PailouType::Ridge, "style 6-5-15", "pailou.lsys");
        let c = common::compile(input, &[]);
        black_box(to_glb_file(&c, dir.path()))
    });
}

/// A guided scene (issue 36): one 700 × 700 guide, `n` seeds of
/// `examples/guided/line.lsys` on a 7-unit lattice, 10 passes of `?X`
/// queries. Before the per-pass grid the time grew with n².
#[divan::bench(args = [2_500, 10_000], sample_count = 5, sample_size = 1)]
fn guided_seeds(bencher: Bencher, n: usize) {
    use lsys::internals::guided;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/guided");
    let mut scene = String::from(
        "steps = 10\n[[guide]]\nname = \"g\"\ngrammar = \"line.lsys\"\n\
         points = [[0, 0], [700, 0], [700, 700], [0, 700]]\n",
    );
    for k in 0..n {
        let (i, j) = (k % 100, k / 100);
        scene.push_str(&format!(
            "[[seeds]]\nguide = \"g\"\nposition = [{}, {}]\nheading = {}\n",
            3 + 7 * i,
            3 + 7 * j,
            (k * 37) % 360
        ));
    }
    let loaded = guided::load_text("scene.toml", &scene, &root, &Default::default())
        .expect("the scene loads");
    bencher
        .counter(ItemsCount::new(n))
        .bench_local(|| black_box(guided::run(&loaded).expect("runs").seeds.len()));
}
