//! The structural check of a job: a built scene and a [`Check`] -> the
//! problems found (supports, interpenetration; `pailou::structure`), or
//! why no check ran.

use std::sync::OnceLock;

use super::job::Check;
use crate::mesh::Scene;
use crate::pailou::graph::RELATIONS;
use crate::pailou::structure::{self, Problem, Rules};

/// The standard library's symbols and relation matrix, read once per
/// process (every studio build and every palette reads them).
pub fn library_rules() -> &'static Rules {
    static RULES: OnceLock<Rules> = OnceLock::new();
    RULES.get_or_init(|| Rules::pailou(RELATIONS).expect("the library's relation matrix reads"))
}

/// The problems `check` finds in `scene`; `Err` says why it could not run
/// (a relation matrix that does not read).
pub(super) fn check(scene: &Scene, check: &Check) -> Result<Vec<Problem>, String> {
    match check {
        Check::None => Ok(Vec::new()),
        Check::Library => Ok(structure::check(scene, library_rules())),
        Check::Relations(text) => Ok(structure::check(scene, &Rules::pailou(text)?)),
    }
}
