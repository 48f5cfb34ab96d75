//! Writing a run's results: every file goes to a temporary name first and is
//! renamed only when all of them were written, so an error never leaves a
//! partial `results.csv` that looks like a result.

use std::fs;
use std::path::{Path, PathBuf};

use crane_runtime::{Solution, State};

use crate::CliError;
use crate::plot;
use crane_models::study::Formulation;
use crane_models::study::Summary;

/// Column names of `results.csv` (docs/numerics.md): `t`, the coordinates, the
/// inputs, `lambda1..lambdam`, the rope tensions.
pub fn header<const N: usize, const M: usize, const A: usize>(
    solution: &Solution<N, M, A>,
    derived: &Derived<N, M, A>,
) -> Vec<String> {
    let info = solution.info;
    let mut names = vec!["t".to_string()];
    names.extend(info.coordinates.iter().map(|s| s.to_string()));
    names.extend(info.inputs.iter().map(|s| s.to_string()));
    names.extend((1..=M).map(|i| format!("lambda{i}")));
    names.extend(info.ropes.iter().map(|r| r.tension.to_string()));
    names.extend(derived.names.iter().map(|s| s.to_string()));
    names
}

fn io_error(context: impl Into<String>) -> impl FnOnce(std::io::Error) -> CliError {
    let context = context.into();
    move |source| CliError::Io { context, source }
}

/// Outputs derived from each state (e.g. the slewing angle), computed as
/// the rows are written.
pub struct Derived<'a, const N: usize, const M: usize, const A: usize> {
    /// Column names.
    pub names: &'static [&'static str],
    /// The values of a state, in the order of `names`.
    pub values: &'a dyn Fn(&State<N, M, A>) -> Vec<f64>,
}

fn write_csv<const N: usize, const M: usize, const A: usize>(
    path: &Path,
    solution: &Solution<N, M, A>,
    derived: &Derived<N, M, A>,
) -> Result<(), CliError> {
    let failed = |e: csv::Error| CliError::Output {
        what: path.display().to_string(),
        message: e.to_string(),
    };
    let mut writer = csv::Writer::from_path(path).map_err(failed)?;
    writer.write_record(header(solution, derived)).map_err(failed)?;
    let mut row: Vec<String> = Vec::new();
    for (i, s) in solution.states.iter().enumerate() {
        row.clear();
        row.push(format!("{}", s.t));
        row.extend(
            s.q.iter()
                .chain(s.u.iter())
                .chain(s.lambda.iter())
                .map(|v| format!("{v:e}")),
        );
        row.extend(solution.tensions_at(i).iter().map(|v| format!("{v:e}")));
        row.extend((derived.values)(s).iter().map(|v| format!("{v:e}")));
        writer.write_record(&row).map_err(failed)?;
    }
    writer.flush().map_err(io_error(format!("writing {}", path.display())))
}

/// The files of one command's output, written under temporary names
/// (`.NAME.partial`) and renamed together by [`commit`](Self::commit): an
/// error before the commit removes them, so no partial file ever looks like
/// a result. Every file `crane` writes goes through one of these.
pub struct Staged {
    dir: PathBuf,
    files: Vec<(PathBuf, PathBuf)>,
    committed: bool,
}

impl Staged {
    /// Output into `dir` (created if missing).
    pub fn new(dir: &Path) -> Result<Self, CliError> {
        fs::create_dir_all(dir).map_err(io_error(format!("creating {}", dir.display())))?;
        Ok(Self {
            dir: dir.to_path_buf(),
            files: Vec::new(),
            committed: false,
        })
    }

    /// The temporary path to write `name` to.
    pub fn path(&mut self, name: &str) -> PathBuf {
        let temporary = self.dir.join(format!(".{name}.partial"));
        self.files.push((temporary.clone(), self.dir.join(name)));
        temporary
    }

    /// Write `name` with `text`.
    pub fn text(&mut self, name: &str, text: impl AsRef<[u8]>) -> Result<(), CliError> {
        let path = self.path(name);
        fs::write(&path, text).map_err(io_error(format!("writing {}", path.display())))
    }

    /// Rename every file to its final name.
    pub fn commit(mut self) -> Result<(), CliError> {
        self.committed = true;
        for (temporary, final_path) in &self.files {
            fs::rename(temporary, final_path).map_err(io_error(format!("renaming to {}", final_path.display())))?;
        }
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            for (temporary, _) in &self.files {
                let _ = fs::remove_file(temporary);
            }
        }
    }
}

/// Write `results.csv`, `summary.json`, the plots and the `extra` files
/// (`(file name, text)`, e.g. `snapshots.svg`) into `out`.
pub fn write_all<const N: usize, const M: usize, const A: usize>(
    out: &Path,
    solution: &Solution<N, M, A>,
    references: Option<&[State<N, M, A>]>,
    summary: &Summary,
    derived: &Derived<N, M, A>,
    extra: &[(String, String)],
) -> Result<(), CliError> {
    let mut staged = Staged::new(out)?;
    let csv = staged.path("results.csv");
    write_csv(&csv, solution, derived)?;
    let json = serde_json::to_string_pretty(summary).map_err(|e| CliError::Output {
        what: "summary.json".into(),
        message: e.to_string(),
    })?;
    staged.text("summary.json", json + "\n")?;
    // the scheme discretises nothing in the dummy-derivative formulation
    let discretised = summary
        .formulation
        .parse::<Formulation>()
        .is_ok_and(Formulation::discretised);
    let method = if discretised {
        format!("{}, {}", summary.formulation, solution.scheme)
    } else {
        summary.formulation.clone()
    };
    for (name, svg) in plot::all(solution, references, &method)?
        .into_iter()
        .chain(extra.iter().cloned())
    {
        staged.text(&name, svg)?;
    }
    staged.commit()
}
