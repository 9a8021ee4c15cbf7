//! cpfg's model objects beyond the L-system file: the view file and the
//! function files `func(id, x)` reads.

pub mod spline;
pub mod view;

/// Whether a file is a cpfg model file (`.l`): read with cpfg's
/// preprocessor, names, dialect and view file.
pub fn is_model_file(name: &str) -> bool {
    name.ends_with(".l")
}
