//! Derive (placeholder).
