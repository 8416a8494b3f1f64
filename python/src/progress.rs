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
        self.interruption.poll();
        let Some(callback) = &self.callback else {
            return;
        };
        let called = Python::attach(|py| callback.call1(py, (stage, done, wanted)).map(drop));
        if let Err(error) = called {
            self.interruption.stop(error);
        }
    }
}
