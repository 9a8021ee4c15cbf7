//! Support: not a stage of the pipeline, but infrastructure the stages
//! share. Nothing of the language goes in or comes out here: what its
//! modules take and give is memory, for whichever stage holds the data.
//! It imports no stage, so every stage may use it.
//!
//! * [`prefault`]: big buffers' addresses and lengths in (the turtle's
//!   chains, the mesher's meshes); their fresh pages backed by a second
//!   core, ahead of their writer, out.

pub mod prefault;
