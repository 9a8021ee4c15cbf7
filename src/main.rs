//! The `lsys` binary: a thin shell over the library (see `src/cli/`).

fn main() {
    std::process::exit(lsys::cli::main());
}
