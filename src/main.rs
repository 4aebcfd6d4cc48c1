//! The `ltikit` binary: see `ltikit --help`.

fn main() {
    std::process::exit(ltikit::cli::main());
}
