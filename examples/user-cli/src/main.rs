//! `my-cranes`: the `crane` command line for the cranes of this crate.

fn main() -> std::process::ExitCode {
    crane::cli::Tool::new(my_cranes::MyCranes).main()
}
