//! The `halfcast` binary: argument parsing and exit codes at the edge; the work is in the library.

mod cli;

/// mimalloc instead of the system's malloc: an SSH session's every frame makes and drops many
/// small strings, spans and buffers (serve_bench, 80x24: about a tenth more clients per core).
#[global_allocator]
static ALLOC: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> std::process::ExitCode {
    cli::run()
}
