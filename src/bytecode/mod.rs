//! Bytecode (placeholder).
