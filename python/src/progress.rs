//! Progress reports to an optional Python callable, called with the GIL re-acquired from inside
//! a computation that runs without it.

use pyo3::prelude::*;
use std::sync::Mutex;

/// An optional callback `progress(stage: str, done: int, wanted: int)`; the first exception it
/// raises is kept and re-raised when the computation returns.
pub struct Progress {
    callback: Option<Py<PyAny>>,
    error: Mutex<Option<PyErr>>,
}

impl Progress {
    /// Wraps `callback` (`None`: silence).
    pub fn new(callback: Option<Py<PyAny>>) -> Self {
        Self {
            callback,
            error: Mutex::new(None),
        }
    }

    /// Calls the callback (after a failure it is not called again).
    pub fn report(&self, stage: &str, done: usize, wanted: usize) {
        let Some(callback) = &self.callback else {
            return;
        };
        let mut error = self.error.lock().unwrap_or_else(|e| e.into_inner());
        if error.is_some() {
            return;
        }
        Python::attach(|py| {
            if let Err(e) = callback.call1(py, (stage, done, wanted)) {
                *error = Some(e);
            }
        });
    }

    /// The callback's exception, if it raised one.
    pub fn finish(self) -> PyResult<()> {
        match self.error.into_inner().unwrap_or_else(|e| e.into_inner()) {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}
