//! The options of a build from the command line's flags: clap's
//! arguments in, the library's `GrammarOptions` and picture settings out.

use super::args::{DeriveRun, LookArgs, PictureArgs, SourceArgs};
use crate::driver;
use crate::GrammarOptions;

/// The options of a build from the command line's flags.
pub(super) fn grammar_options(
    defines: &[(String, String)],
    source: Option<&SourceArgs>,
    run: &DeriveRun,
    look: &LookArgs,
) -> GrammarOptions {
    let mut o = GrammarOptions::default().defines_from(defines);
    if let Some(s) = source {
        o = s.apply(o);
    }
    o = o
        .steps(run.steps)
        .max_modules(run.max_modules)
        .max_params(run.max_params);
    if let Some(seed) = run.seed {
        o = o.seed(seed);
    }
    look.apply(o)
}

pub(super) fn picture(pic: &PictureArgs) -> driver::Picture {
    driver::Picture {
        view: pic.view,
        style: pic.style,
        width: pic.size.0,
        height: pic.size.1,
        ..Default::default()
    }
}
