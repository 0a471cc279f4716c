//! The `unimo` binary: a thin shell around [`unimo_cli::run`].

/// The compiler allocates many small tree nodes; mimalloc serves them about twice as
/// fast as the system allocator (see `docs/results/parser.md`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    std::process::exit(unimo_cli::run());
}
