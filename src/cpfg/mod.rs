//! cpfg's model objects beyond the L-system file: the view file and the
//! function files `func(id, x)` reads.

pub mod view;
