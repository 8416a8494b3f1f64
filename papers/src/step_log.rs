//! [`StepLog`]: the reproduction's log, one line per step on stderr, with the time since the
//! start and the step's own time, so that a long reproduction run shows where it is and where the time goes.

use std::time::Instant;

/// Writes progress lines `[  12.3 s] message` to stderr (nothing when quiet).
#[derive(Debug)]
pub struct StepLog {
    start: Instant,
    quiet: bool,
}

impl StepLog {
    /// A progress writer starting its clock now.
    pub fn new(quiet: bool) -> Self {
        Self {
            start: Instant::now(),
            quiet,
        }
    }

    /// Seconds since [`StepLog::new`].
    pub fn elapsed(&self) -> f64 {
        self.start.elapsed().as_secs_f64()
    }

    /// Prints one line.
    pub fn note(&self, message: impl AsRef<str>) {
        if !self.quiet {
            eprintln!("[{:8.1} s] {}", self.elapsed(), message.as_ref());
        }
    }

    /// Runs `step`, announcing it before and reporting its wall-clock time after; returns its
    /// result and the seconds it took.
    pub fn step<T, E>(
        &self,
        name: &str,
        step: impl FnOnce() -> Result<T, E>,
    ) -> Result<(T, f64), E> {
        self.note(format!("{name} ..."));
        let start = Instant::now();
        let value = step()?;
        let seconds = start.elapsed().as_secs_f64();
        self.note(format!(
            "{name}: {}",
            tvf_figures::numbers::seconds(seconds)
        ));
        Ok((value, seconds))
    }
}
