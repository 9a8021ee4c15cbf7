//! Environments of Open L-systems: what answers cpfg's `?E` query modules
//! between derivation steps. Input: the queries of one environment pass
//! (each `?E`'s parameters and the turtle's state where it stands, as the
//! communication file formats them); output: for each query, the
//! parameters the environment sets. The programs are native versions of
//! the Virtual Laboratory's environmental programs (`ENVIRO/` in the vlab
//! sources): [`collision`] (honda81), [`light`] (chiba), [`density`] and
//! [`clover`]; a
//! model chooses one with its `.e` communication file ([`communication`]).
//!
//! This stage does no I/O and knows nothing of the turtle or of derive:
//! the simulation loop (`src/simulation/`) interprets the string,
//! builds the [`Query`] list and writes the replies back.

pub mod clover;
pub mod collision;
pub mod communication;
pub mod density;
mod error;
pub mod format;
mod header;
pub mod light;
mod sgi;

pub use communication::{configure, EnvironmentSpec, Field};
pub use error::EnvironmentError;
pub use header::environment_header;

/// One `?E` of an environment pass, as the environment receives it.
#[derive(Clone, Debug, PartialEq)]
pub struct Query {
    /// The module's position in the string (replies are keyed by it).
    pub index: usize,
    /// Its parameters.
    pub params: Vec<f64>,
    /// The turtle's state there, each field rounded as the communication
    /// file's format prints it (cpfg sends text); `None` for a field the
    /// file does not ask for.
    pub position: Option<[f32; 3]>,
    pub heading: Option<[f32; 3]>,
    pub left: Option<[f32; 3]>,
    pub up: Option<[f32; 3]>,
    pub line_width: Option<f32>,
    pub scale: Option<f32>,
}

/// What the environment sets in one query: `Some(v)` overwrites that
/// parameter, `None` leaves it as the grammar wrote it.
pub type Reply = Vec<Option<f64>>;

/// An environmental program: sees every query of a pass, then answers
/// (cpfg's "delayed" mode, which every vlab program uses). Answers must
/// depend only on the queries and their order, never on hashing.
pub trait EnvironmentalProgram: Send {
    /// One reply per query, in the queries' order.
    fn respond(&mut self, queries: &[Query]) -> Vec<Reply>;
}
