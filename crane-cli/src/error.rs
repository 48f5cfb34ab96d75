//! The errors `crane` reports (then it exits non-zero), one line each.

use crane_models::study::StudyError;

/// Everything a command can fail with.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    #[error("unknown model `{name}`; `{program} list` shows the models")]
    UnknownModel { name: String, program: String },
    #[error(transparent)]
    Runtime(#[from] crane_runtime::Error),
    #[error(transparent)]
    Study(#[from] StudyError),
    #[error("{context}: {source}")]
    Io { context: String, source: std::io::Error },
    #[error("writing {what}: {message}")]
    Output { what: String, message: String },
    #[error("writing to standard output: {0}")]
    Stdout(std::io::Error),
    #[error("--repeat must be at least 1")]
    NoRepeats,
    #[error("--repeat {0}: at most {max} timed runs", max = crate::commands::bench::MAX_REPEAT)]
    TooManyRepeats(usize),
    #[error("{flag} `{name}` is given twice ({first} and {second}): give each name once")]
    Repeated {
        flag: &'static str,
        name: String,
        first: f64,
        second: f64,
    },
    #[error("--plant `{0}`: expected NAME=VALUE, e.g. --plant m_l=110")]
    Plant(String),
    #[error(
        "--settle {}: the settling window must be a positive number of seconds, at most {}",
        crane_runtime::error::Number(*.0),
        crane_models::study::replay::MAX_SETTLE
    )]
    Settle(f64),
    #[error("the scenario's [plant] table ({0}) applies only to a replay: add --replay")]
    PlantWithoutReplay(String),
    #[error("--feedback `{0}`: {1}")]
    Feedback(String, crane_models::study::replay::BadFeedback),
    #[error(transparent)]
    Scenario(#[from] crate::scenario::ScenarioError),
    #[error("the replay failed: {source}; the inverse run's results were written to {out}")]
    ReplayFailed { source: StudyError, out: String },
    #[error("infeasible (--strict): {problems}; the results were still written to {out}")]
    Infeasible { problems: String, out: String },
    #[error("{0}")]
    Planning(String),
    #[error(
        "no FMU library at {0}: build it (the built-in cranes' with `cargo build --release -p crane-fmu`, a tool's \
         own with `cargo build --release` of its crate, a `cdylib` that calls `export_fmu!`) or give --library"
    )]
    NoFmuLibrary(String),
    #[error(transparent)]
    Package(#[from] crane_fmi::package::PackageError),
    #[error(
        "the scenario's [plant] table ({0}) applies only to a replay (`crane run --replay`); an FMU computes the \
         inputs of the crane the scenario's parameters describe: remove [plant] to package it"
    )]
    FmuPlant(String),
    #[error("the run the FMU starts from: {0}")]
    FmuStart(#[from] crane_fmi::start::StartError),
}
