//! The session's progress ([`crate::driver::session::Meter`]) -> the
//! terminal's progress bar ([`crate::progress::Progress`]), one per long
//! operation, cleared when the operation ends.

use crate::driver::session::Meter;
use crate::driver::Stage;
use crate::progress::Progress;

/// A progress bar on standard error for one operation.
pub struct Bar(Progress);

impl Bar {
    pub fn new() -> Bar {
        Bar(Progress::new(true))
    }
}

impl Meter for Bar {
    fn stage(&self, stage: Stage) {
        self.0.stage(stage);
    }

    fn message(&self, what: &'static str) {
        self.0.message(what);
    }
}
