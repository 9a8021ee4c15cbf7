//! `lsys build SCENE.toml` and `lsys render SCENE.toml`: a guided scene
//! (docs/guided.md) in, a model file or a picture out; `--guides` adds the
//! guides and links, `--stats` prints seeds, messages and time per step.

use std::path::{Path, PathBuf};

use super::args::{ModelArgs, PictureArgs};
use super::options::{grammar_options, picture};
use super::report::write_failed;
use super::EX_OK;
use crate::driver::{self, Format, GuidedJob, Output};

/// Runs, meshes and writes a guided scene; the exit code.
pub fn build_scene(
    m: &ModelArgs,
    out: &Path,
    pic: &PictureArgs,
    format: Format,
    color: bool,
) -> i32 {
    let job = GuidedJob {
        path: PathBuf::from(&m.common.file),
        options: grammar_options(&m.common.define, Some(&m.common.source), &m.run, &m.look),
        guides: m.look.guides,
        output: Output::File {
            path: out.to_path_buf(),
            format,
            picture: picture(pic),
        },
    };
    match driver::run_guided(&job) {
        Ok(done) => {
            if m.look.stats {
                println!("{}", done.stats());
            }
            EX_OK
        }
        Err(f) => write_failed(f.reason, color),
    }
}
