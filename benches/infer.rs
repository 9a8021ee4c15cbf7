//! `lsys infer` (issue 33): a 1000 x 600 elevation drawing of
//! `examples/shapes/hall.lsys` (drawn once by `lsys render --style lines`)
//! to its labelled shape tree and grammar, as PNG bytes in memory and as
//! the hand-laid SVG of `examples/drawings/seven-bay-palace.svg`; and a
//! Pailou's front, read by synthesis. The issue asks for under a second
//! at 1000 x 600.

mod common;

use divan::{black_box, Bencher};
use lsys::internals::build::{self, BuildOptions};
use lsys::internals::export::render::{self, RenderOptions, Style, View};
use lsys::internals::infer::{self, InferOptions};
use lsys::internals::load::Input;

fn main() {
    divan::main();
}

/// The hall's front elevation as PNG bytes, `w` x `h`.
fn hall_png(w: u32, h: u32) -> Vec<u8> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/shapes/hall.lsys");
    let c = common::compile(Input::Path(path.into()), &[]);
    let built = build::build(&c, &BuildOptions::default()).expect("builds");
    let opts = RenderOptions {
        view: View::Front,
        style: Style::Lines,
        width: w,
        height: h,
        ..RenderOptions::default()
    };
    let mut png = Vec::new();
    render::write_png(&render::render(&built.scene, &opts), &mut png).expect("encodes");
    png
}

fn infer_bytes(bencher: Bencher, bytes: Vec<u8>) {
    bencher.bench_local(|| {
        black_box(infer::infer(&bytes, "bench", &InferOptions::default()).expect("infers"))
    });
}

#[divan::bench(sample_count = 10, sample_size = 1)]
fn hall_1000x600_png(bencher: Bencher) {
    infer_bytes(bencher, hall_png(1000, 600));
}

#[divan::bench(sample_count = 10, sample_size = 1)]
fn hall_2000x1200_png(bencher: Bencher) {
    infer_bytes(bencher, hall_png(2000, 1200));
}

#[divan::bench(sample_count = 10, sample_size = 1)]
fn palace_svg(bencher: Bencher) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/drawings/seven-bay-palace.svg"
    );
    infer_bytes(bencher, std::fs::read(path).expect("the example drawing"));
}

/// A Pailou's front (std:pailou's 4-3-7, ridge type), read as `lsys
/// infer` reads it: the driver tells it from a hall and reads it by
/// synthesis (every style of four pillars drawn and compared).
#[divan::bench(sample_count = 10, sample_size = 1)]
fn pailou_4_3_7_1000x600_png(bencher: Bencher) {
    use lsys::driver::{infer_edited, read_drawing, Pailou, PailouType};
    let p = Pailou::style("4-3-7", PailouType::Ridge).expect("a style");
    let scene = lsys::driver::run(&p.job(lsys::Grammar::options()), &mut |_| {})
        .expect("builds")
        .scene;
    let opts = RenderOptions {
        view: View::Front,
        style: Style::Lines,
        width: 1000,
        height: 600,
        ..RenderOptions::default()
    };
    let mut png = Vec::new();
    render::write_png(&render::render(scene.mesh(), &opts), &mut png).expect("encodes");
    bencher.bench_local(|| {
        let ink = read_drawing(&png, "bench").expect("reads");
        black_box(infer_edited(&ink, "bench", &[], &[], &InferOptions::default()).expect("infers"))
    });
}
