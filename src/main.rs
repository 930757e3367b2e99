//! The rover-terrain command line: a thin dispatcher over one module per command
//! (`src/cli/`).

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    cli::main()
}
