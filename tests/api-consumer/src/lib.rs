//! A downstream crate of `lsys` (library only): the algae system of ABOP
//! chapter 1 as a function, so that the tests below exercise a real
//! caller of the public API.

use lsys::{Derived, Diagnostics, Grammar};

/// Lindenmayer's algae, `steps` steps.
pub fn algae(steps: u32) -> Result<Derived, Diagnostics> {
    Grammar::from_str("algae.lsys", "axiom: A\nA --> A B\nB --> A\n")?.derive(steps)
}
