//! A progress bar for runs that take longer than about a second (indicatif),
//! drawn on stderr only when stdout is a terminal and `--quiet` is not given.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Runs shorter than this never show a bar.
const DELAY: Duration = Duration::from_secs(1);

/// Progress of one run; call [`Progress::tick`] after every step.
pub struct Progress {
    bar: Option<ProgressBar>,
    started: Instant,
    enabled: bool,
}

impl Progress {
    /// A progress report for a run labelled `label`; silent if `quiet` or if
    /// stdout is not a terminal.
    pub fn new(label: &str, quiet: bool) -> Self {
        let enabled = !quiet && std::io::stdout().is_terminal();
        let bar = enabled.then(|| {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
            if let Ok(style) = ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} steps, {eta} left") {
                bar.set_style(style.progress_chars("=> "));
            }
            bar.set_message(label.to_string());
            bar
        });
        Self {
            bar,
            started: Instant::now(),
            enabled,
        }
    }

    /// Step `step` of `steps` is done.
    pub fn tick(&mut self, step: usize, steps: usize) {
        let Some(bar) = &self.bar else { return };
        if bar.is_hidden() {
            if !self.enabled || self.started.elapsed() < DELAY {
                return;
            }
            bar.set_length(steps as u64);
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        bar.set_position(step as u64);
    }

    /// Remove the bar (if it was shown).
    pub fn finish(self) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
    }
}
