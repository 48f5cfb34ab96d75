//! `crane`: the command line of the built-in cranes (the library
//! [`crane_cli`] with [`BuiltIn`](crane_models::BuiltIn) as its registry).

use std::process::ExitCode;

fn main() -> ExitCode {
    crane_cli::Tool::new(crane_models::BuiltIn)
        .program("crane")
        .fmu_library("libcrane_fmu.so")
        .main()
}
