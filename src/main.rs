//! The `halfcast` binary: argument parsing and exit codes at the edge; the work is in the library.

mod cli;

fn main() -> std::process::ExitCode {
    cli::run()
}
