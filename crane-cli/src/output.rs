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

/// One line on standard output (what the crate's `say!` prints): an
/// error, such as a full disk behind `> file` or a reader that closed the
/// pipe (`| head -1`), is returned, where `println!` would panic.
pub fn say(line: std::fmt::Arguments) -> Result<(), CliError> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_fmt(line)
        .and_then(|()| stdout.write_all(b"\n"))
        .and_then(|()| stdout.flush())
        .map_err(CliError::Stdout)
}

/// Whether `dir` could take a command's output, checked before the command
/// computes anything and leaving nothing behind: `dir` is a folder, or does
/// not exist yet and its nearest existing ancestor is one, and a file can
/// be created there (a probe, removed at once).
pub fn check_writable(dir: &Path) -> Result<(), CliError> {
    let refuse = |message: String| CliError::Output {
        what: dir.display().to_string(),
        message,
    };
    let mut existing = dir;
    while fs::symlink_metadata(existing).is_err() {
        match existing.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => existing = parent,
            _ => {
                existing = Path::new(".");
                break;
            }
        }
    }
    if !existing.is_dir() {
        return Err(refuse(format!("{} is not a folder", existing.display())));
    }
    let probe = existing.join(format!(".crane-probe-{}", std::process::id()));
    match fs::OpenOptions::new().write(true).create_new(true).open(&probe) {
        Ok(_) => {
            let _ = fs::remove_file(&probe);
            Ok(())
        }
        Err(error) => Err(refuse(format!(
            "cannot create files in {}: {error}",
            existing.display()
        ))),
    }
}

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
    file: fs::File,
    solution: &Solution<N, M, A>,
    derived: &Derived<N, M, A>,
) -> Result<(), CliError> {
    let failed = |e: csv::Error| CliError::Output {
        what: path.display().to_string(),
        message: e.to_string(),
    };
    let mut writer = csv::Writer::from_writer(file);
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

/// A command's claim on its output folder, from before it computes to its
/// end: an exclusive lock on `DIR/.crane.lock`, taken without waiting. A
/// second command into the same folder is refused while the first runs
/// (the lock once ordered only the writes: a run that started later and
/// finished first was replaced by the other without a word). The folders
/// the claim created are removed again if the command ends without writing
/// into them.
pub struct Claim {
    dir: PathBuf,
    /// The outermost folder the claim created (`dir` or an ancestor), if
    /// it created any.
    created: Option<PathBuf>,
    /// Held for the claim's lifetime.
    _lock: fs::File,
}

/// The folder of the live [`Claim`] of this process, which its [`Staged`]
/// writes under (without locking again: a second lock on the same file
/// would wait for the first).
static CLAIMED: std::sync::Mutex<Option<PathBuf>> = std::sync::Mutex::new(None);

/// The claimed folder, also after a panic elsewhere held the mutex.
fn claimed() -> std::sync::MutexGuard<'static, Option<PathBuf>> {
    CLAIMED.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

impl Claim {
    /// Claim `dir` (created if missing, with its parents), or refuse if
    /// another command holds it.
    pub fn new(dir: &Path) -> Result<Self, CliError> {
        let created = dir
            .ancestors()
            .take_while(|folder| !folder.as_os_str().is_empty() && fs::symlink_metadata(folder).is_err())
            .last()
            .map(Path::to_path_buf);
        let (lock_path, lock) = open_lock(dir)?;
        let claim = Self {
            dir: dir.to_path_buf(),
            created,
            _lock: lock,
        };
        match claim._lock.try_lock() {
            Ok(()) => {}
            Err(fs::TryLockError::WouldBlock) => {
                return Err(CliError::Output {
                    what: dir.display().to_string(),
                    message: "another run of crane is writing into this folder: wait for it to end, or give \
                              another --out"
                        .into(),
                });
            }
            Err(fs::TryLockError::Error(error)) => {
                return Err(io_error(format!("locking {}", lock_path.display()))(error));
            }
        }
        *claimed() = Some(dir.to_path_buf());
        Ok(claim)
    }
}

impl Drop for Claim {
    /// Release the claim; a folder it created and nothing was written into
    /// (but its lock file) is removed.
    fn drop(&mut self) {
        *claimed() = None;
        let Some(created) = &self.created else {
            return;
        };
        let only_the_lock = fs::read_dir(&self.dir)
            .is_ok_and(|entries| entries.filter_map(Result::ok).all(|entry| entry.file_name() == LOCK));
        if only_the_lock {
            let _ = fs::remove_file(self.dir.join(LOCK));
            // the folders it created, innermost first, while they are empty
            for folder in self.dir.ancestors() {
                if fs::remove_dir(folder).is_err() || folder == created {
                    break;
                }
            }
        }
    }
}

/// The files of one command's output, written under temporary names
/// (`.NAME.partial`) and renamed together by [`commit`](Self::commit): an
/// error before the commit, or SIGINT/SIGTERM ([`remove_partials_on_signals`]),
/// removes them, so no partial file ever looks like a result. Every file
/// `crane` writes goes through one of these.
///
/// A folder holds one run's output: the writer holds an exclusive lock on
/// `DIR/.crane.lock` from [`new`](Self::new) to the end (a second `crane`
/// writing into the same folder waits for it; a command's [`Claim`] holds
/// it from its start), and the commit removes the
/// files an earlier run wrote there (listed in `DIR/.crane-outputs`) that
/// this one does not, so a replay.csv or sweep.svg of another kind of run
/// cannot stay beside this run's summary. Other files are left alone.
pub struct Staged {
    dir: PathBuf,
    files: Vec<(PathBuf, PathBuf)>,
    committed: bool,
    /// Held for the lock's lifetime.
    _lock: fs::File,
}

/// The lock file of an output folder.
const LOCK: &str = ".crane.lock";

/// `dir` (created if missing, with its parents) and its lock file, opened
/// (not locked).
fn open_lock(dir: &Path) -> Result<(PathBuf, fs::File), CliError> {
    fs::create_dir_all(dir).map_err(io_error(format!("creating {}", dir.display())))?;
    let lock_path = dir.join(LOCK);
    let lock = fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&lock_path)
        .map_err(io_error(format!("opening {}", lock_path.display())))?;
    Ok((lock_path, lock))
}

/// The list of the files the last run wrote into an output folder.
const MANIFEST: &str = ".crane-outputs";

/// The partial files of every [`Staged`] not yet committed, for the signal
/// handler. The lock is held while a partial file is created and while a
/// commit renames, and the handler exits holding it: a signal comes either
/// before a file exists (it is never created) or after it is registered (it
/// is removed), and either before a commit (nothing renamed) or after it.
static PARTIALS: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// The list of partial files, also after a panic elsewhere held the lock.
fn partials() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    PARTIALS.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Remove every partial file and exit with 130 on SIGINT or SIGTERM (called
/// once, at start-up).
pub fn remove_partials_on_signals() {
    let installed = ctrlc::set_handler(|| {
        // held until the process ends: no partial file is created after this
        let partials = partials();
        for path in partials.iter() {
            let _ = fs::remove_file(path);
        }
        eprintln!("interrupted: no partial output left behind");
        std::process::exit(130);
    });
    // without a handler (another one is installed) a signal still stops the run
    let _ = installed;
}

/// Write one file `path` (not a folder's output: no lock, no list of
/// outputs) through a temporary file beside it, registered for the signal
/// handler and renamed when whole: an error or SIGINT/SIGTERM on the way
/// leaves `path` as it was and no partial file.
pub fn write_whole(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    if let Some(kind) = crane_models::files::not_a_regular_file(path) {
        return Err(CliError::Output {
            what: path.display().to_string(),
            message: format!(
                "it exists and is {kind}, not a regular file, which crane does not replace: remove it or choose \
                 another --out"
            ),
        });
    }
    let dir = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    fs::create_dir_all(dir).map_err(io_error(format!("creating {}", dir.display())))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temporary = dir.join(format!(".{name}.{}.partial", std::process::id()));
    let written = {
        let mut partials = partials();
        partials.push(temporary.clone());
        fs::File::create(&temporary).map_err(io_error(format!("creating {}", temporary.display())))
    };
    let result = written.and_then(|mut file| {
        std::io::Write::write_all(&mut file, bytes).map_err(io_error(format!("writing {}", temporary.display())))?;
        let mut partials = partials();
        let renamed = fs::rename(&temporary, path).map_err(io_error(format!("renaming to {}", path.display())));
        partials.retain(|p| p != &temporary);
        renamed
    });
    if result.is_err() {
        let _ = fs::remove_file(&temporary);
        partials().retain(|p| p != &temporary);
    }
    result
}

impl Staged {
    /// Output into `dir` (created if missing), once its lock is ours.
    pub fn new(dir: &Path) -> Result<Self, CliError> {
        let (lock_path, lock) = open_lock(dir)?;
        // under this process's claim the folder is ours already
        if claimed().as_deref() != Some(dir) {
            lock.lock()
                .map_err(io_error(format!("locking {}", lock_path.display())))?;
        }
        Ok(Self {
            dir: dir.to_path_buf(),
            files: Vec::new(),
            committed: false,
            _lock: lock,
        })
    }

    /// Create the temporary file for `name`, registered for the signal
    /// handler in the same critical section; returns its path and handle.
    pub fn create(&mut self, name: &str) -> Result<(PathBuf, fs::File), CliError> {
        let destination = self.dir.join(name);
        if let Some(kind) = crane_models::files::not_a_regular_file(&destination) {
            return Err(CliError::Output {
                what: destination.display().to_string(),
                message: format!(
                    "it exists and is {kind}, which crane does not replace: remove it or choose another --out"
                ),
            });
        }
        let temporary = self.dir.join(format!(".{name}.partial"));
        let mut partials = partials();
        partials.push(temporary.clone());
        self.files.push((temporary.clone(), self.dir.join(name)));
        let file = fs::File::create(&temporary).map_err(io_error(format!("creating {}", temporary.display())))?;
        drop(partials);
        Ok((temporary, file))
    }

    /// Write `name` with `text`.
    pub fn text(&mut self, name: &str, text: impl AsRef<[u8]>) -> Result<(), CliError> {
        let (path, mut file) = self.create(name)?;
        std::io::Write::write_all(&mut file, text.as_ref()).map_err(io_error(format!("writing {}", path.display())))
    }

    /// Rename every file to its final name, remove what an earlier run left
    /// that this one does not write, and list this run's files.
    pub fn commit(mut self) -> Result<(), CliError> {
        {
            // all renamed or none: the signal handler waits for this
            let mut partials = partials();
            for (temporary, final_path) in &self.files {
                fs::rename(temporary, final_path).map_err(io_error(format!("renaming to {}", final_path.display())))?;
            }
            self.forget(&mut partials);
            self.committed = true;
        }
        let names: Vec<String> = self
            .files
            .iter()
            .filter_map(|(_, path)| path.file_name().map(|n| n.to_string_lossy().into_owned()))
            .collect();
        let manifest = self.dir.join(MANIFEST);
        if let Ok(earlier) = fs::read_to_string(&manifest) {
            for stale in earlier.lines().filter(|name| !names.iter().any(|n| n == name)) {
                // only plain names this tool wrote, never a path elsewhere
                if !stale.is_empty() && !stale.contains('/') && !stale.starts_with('.') {
                    let _ = fs::remove_file(self.dir.join(stale));
                }
            }
        }
        fs::write(&manifest, names.join("\n") + "\n").map_err(io_error(format!("writing {}", manifest.display())))
    }

    /// Drop this writer's partial files from the signal handler's list.
    fn forget(&self, partials: &mut Vec<PathBuf>) {
        partials.retain(|p| !self.files.iter().any(|(temporary, _)| temporary == p));
    }
}

impl Drop for Staged {
    /// Without a commit (an error on the way), remove the partial files.
    fn drop(&mut self) {
        if !self.committed {
            for (temporary, _) in &self.files {
                let _ = fs::remove_file(temporary);
            }
            self.forget(&mut partials());
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
    let (csv, file) = staged.create("results.csv")?;
    write_csv(&csv, file, solution, derived)?;
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
    // stable inversion acts before the move starts and after it ends: the
    // plots mark where the load moves
    let moving = summary
        .stable_inversion
        .as_ref()
        .map(|inversion| (summary.t0 + inversion.t_pre, summary.tf - inversion.t_post));
    for (name, svg) in plot::all(solution, references, &method, moving)?
        .into_iter()
        .chain(extra.iter().cloned())
    {
        staged.text(&name, svg)?;
    }
    staged.commit()
}
