//! The `spectrace` command.

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = spectrace::cli::Cli::parse();
    match spectrace::cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
