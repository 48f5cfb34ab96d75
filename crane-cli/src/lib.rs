//! `crane`: run a crane's inverse dynamics and write results, summary and plots.
//!
//! ```text
//! crane list
//! crane run navy-planar [--scenario FILE.toml] [--dt 0.01] [--tf 4] [--scheme bdf4] [--out out/navy-planar] [--strict]
//! crane convergence navy-planar [--formulation minimal] [--scheme bdf4]
//! crane bench navy-planar [--dt 0.01] [--scheme bdf4] [--repeat 20] [--json]
//! crane fmu navy-planar [--out out/navy-planar.fmu] [--library target/release/libcrane_fmu.so]
//! crane fastest navy-planar --limit u2=150 [--min-tension N1=0] [--scenario FILE] [--json]
//! crane sweep navy-planar --param m_l=80:120:5 [--duration 3:5:5] [--limit u2=150]
//! ```
//!
//! This file holds the command line (clap) and the dispatch; each command
//! lives in `commands/`, what a run means in `crane_models::study`.

mod commands;
mod error;
mod output;
mod plot;
mod progress;
mod scenario;
mod snapshots;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

pub use error::CliError;

/// Inverse dynamics of underactuated cranes: the torques that move the load
/// exactly along a prescribed path (backward Euler or BDF-k on the minimally
/// extended index-3 DAEs).
#[derive(Parser, Debug)]
#[command(name = "crane", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// List the built-in models with their sizes n, m, a, f.
    List,
    /// Run a model on its paper maneuver or a scenario; write results.csv, summary.json and SVG plots.
    Run(commands::run::RunArgs),
    /// Time repeated runs without writing files; print median wall time per run and per step.
    Bench(commands::bench::BenchArgs),
    /// Convergence study: the relative error of u at t = 1.5 s (eq. 48) for
    /// dt = 0.1 ... 0.001 and the observed orders; writes convergence.svg
    /// (log-log, like Figs. 7 and 16, with the slope of the scheme's order)
    /// and convergence.csv.
    Convergence(commands::convergence::ConvergenceArgs),
    /// The shortest duration of the move's shape (start, end and profile of
    /// the scenario or the default manoeuvre, time scaled) for which every
    /// torque limit and tension floor holds; writes fastest.json and plots
    /// of u and the tensions with the limits.
    Fastest(commands::plan::FastestArgs),
    /// Peaks and feasibility over a grid of parameters (and durations), in
    /// parallel: sweep.csv, and for two swept quantities a heat map sweep.svg.
    Sweep(commands::plan::SweepArgs),
    /// Write an FMI 2.0 co-simulation FMU of a built-in model (the inverse
    /// model: load target in, inputs, coordinates, multipliers and tensions
    /// out); see the README, "Using a crane in Simulink, Modelica or Python".
    Fmu(commands::fmu::FmuArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    output::remove_partials_on_signals();
    let result = match cli.command {
        Command::List => commands::list::list(),
        Command::Run(args) => commands::run::run(args),
        Command::Bench(args) => commands::bench::bench(args),
        Command::Convergence(args) => commands::convergence::convergence(args),
        Command::Fastest(args) => commands::plan::fastest(args),
        Command::Sweep(args) => commands::plan::sweep(args),
        Command::Fmu(args) => commands::fmu::fmu(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}
