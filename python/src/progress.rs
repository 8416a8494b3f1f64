//! Progress reports to an optional Python callable, called with the GIL re-acquired from inside
//! a computation that runs without it; each report is also where the computation notices Ctrl+C
//! ([`Interruption::poll`]).

use crate::interrupt::Interruption;
use pyo3::prelude::*;

/// An optional callback `progress(stage: str, done: int, wanted: int)`.
pub struct Progress<'a> {
    callback: Option<Py<PyAny>>,
    interruption: &'a Interruption,
}

impl<'a> Progress<'a> {
    /// Wraps `callback` (`None`: silence); stops through `interruption`.
    pub fn new(callback: Option<Py<PyAny>>, interruption: &'a Interruption) -> Self {
        Self {
            callback,
            interruption,
        }
    }

    /// Handles pending signals, then calls the callback. An exception of either (Ctrl+C's
    /// `KeyboardInterrupt`, or whatever the callback raises) stops the computation at once and
    /// is raised when it has unwound ([`Interruption::stop`]).
    pub fn report(&self, stage: &str, done: usize, wanted: usize) {
        let (done, wanted) = (done as u64, wanted as u64);
        report_progress(
            self.callback.as_ref(),
            self.interruption,
            stage,
            done,
            wanted,
        );
    }
}

/// [`Progress::report`] for a callback held elsewhere (`None`: only the signals are handled).
pub fn report_progress(
    callback: Option<&Py<PyAny>>,
    interruption: &Interruption,
    stage: &str,
    done: u64,
    wanted: u64,
) {
    interruption.poll();
    let Some(callback) = callback else {
        return;
    };
    let called = Python::attach(|py| callback.call1(py, (stage, done, wanted)).map(drop));
    if let Err(error) = called {
        interruption.stop(error);
    }
}
