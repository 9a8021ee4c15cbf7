//! placeholder
pub mod error;
pub mod rng;
pub mod store;
