//! Progress reporting shared by every subcommand: a global `--quiet` switch, progress bars
//! (indicatif) on a terminal and plain, throttled lines when stderr is redirected. Used by
//! basis computations and by sequence compression and decompression (one step per frame;
//! [`Progress::update`] may be called from several threads).
//!
//! ```text
//! let progress = Progress::new("basis");
//! let callback = progress.basis_callback();
//! compute_basis(&complex, &BasisRequest::pairs(100).with_progress(&callback))?;
//! progress.finish("300 fields in 4.2 s");
//! ```
//!
//! Notes (`note`) go to stderr unless `--quiet` is given; warnings (`warn`) always do.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::Duration;
use tvf_spectral::BasisProgress;

static QUIET: AtomicBool = AtomicBool::new(false);

/// Silences progress bars and notes for the rest of the process (`--quiet`).
pub fn set_quiet(quiet: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
}

/// Whether `--quiet` was given.
pub fn is_quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// An informational line on stderr (hidden by `--quiet`).
pub fn note(message: impl AsRef<str>) {
    if !is_quiet() {
        eprintln!("{}", message.as_ref());
    }
}

/// A warning on stderr (always shown).
pub fn warn(message: impl AsRef<str>) {
    eprintln!("warning: {}", message.as_ref());
}

/// How progress is shown.
enum Sink {
    /// `--quiet`: nothing.
    Hidden,
    /// A progress bar on a terminal.
    Bar(ProgressBar),
    /// Plain lines (stderr is a file or a pipe): one per stage and one per quarter of a stage.
    Lines(Mutex<LineState>),
}

/// What the plain-line reporter printed last, so that it prints only on change.
struct LineState {
    stage: String,
    quarter: usize,
}

/// Progress of one long task (a basis computation, a sequence of frames).
pub struct Progress {
    task: String,
    sink: Sink,
}

impl Progress {
    /// Progress of the task called `task` (used as the bar's prefix or each line's prefix).
    pub fn new(task: impl Into<String>) -> Self {
        let task = task.into();
        let sink = if is_quiet() {
            Sink::Hidden
        } else if std::io::stderr().is_terminal() {
            let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr());
            let style = ProgressStyle::with_template(
                "{prefix:>12} [{bar:30}] {pos}/{len} {msg} ({elapsed})",
            )
            .map(|s| s.progress_chars("=> "))
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            bar.set_style(style);
            bar.set_prefix(task.clone());
            bar.enable_steady_tick(Duration::from_millis(200));
            Sink::Bar(bar)
        } else {
            Sink::Lines(Mutex::new(LineState {
                stage: String::new(),
                quarter: usize::MAX,
            }))
        };
        Progress { task, sink }
    }

    /// Reports `done` of `wanted` items of `stage` (e.g. "co-integrable eigenfields").
    pub fn update(&self, stage: &str, done: usize, wanted: usize) {
        match &self.sink {
            Sink::Hidden => {}
            Sink::Bar(bar) => {
                bar.set_length(wanted as u64);
                bar.set_position(done.min(wanted) as u64);
                bar.set_message(stage.to_string());
            }
            Sink::Lines(state) => {
                let Ok(mut state) = state.lock() else { return };
                let quarter = (4 * done.min(wanted)).checked_div(wanted).unwrap_or(4);
                // Parallel workers may report out of order: print only progress beyond the last
                // line of the same stage.
                if state.stage != stage || state.quarter == usize::MAX || quarter > state.quarter {
                    eprintln!("{}: {stage} {done}/{wanted}", self.task);
                    state.stage = stage.to_string();
                    state.quarter = quarter;
                }
            }
        }
    }

    /// A callback for [`tvf_spectral::BasisRequest::with_progress`].
    pub fn basis_callback(&self) -> impl Fn(&BasisProgress) + '_ {
        move |p: &BasisProgress| self.update(p.stage.name(), p.done, p.wanted)
    }

    /// Ends the task with a summary line (hidden by `--quiet`).
    pub fn finish(&self, summary: impl AsRef<str>) {
        if let Sink::Bar(bar) = &self.sink {
            bar.finish_and_clear();
        }
        if !matches!(self.sink, Sink::Hidden) {
            eprintln!("{}: {}", self.task, summary.as_ref());
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Sink::Bar(bar) = &self.sink {
            bar.finish_and_clear();
        }
    }
}
