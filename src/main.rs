//! The `unimo` binary: a thin shell around [`unimo_cli::run`].

fn main() {
    std::process::exit(unimo_cli::run());
}
