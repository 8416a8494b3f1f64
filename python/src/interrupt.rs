//! Ctrl+C (and any exception Python raises from a signal handler) during a long computation:
//! the computation runs without the GIL, so Python's handler only sets a flag; [`Interruption`]
//! polls it from the computation's progress reports and from every call into a Python builder,
//! and stops the computation by unwinding with [`StopRun`] (the payload the conformance runner
//! passes on, and the eigensolver's interval jobs stop for). [`interruptible`] runs the
//! computation, catches that unwinding and raises the exception — `KeyboardInterrupt` — in
//! Python, promptly, instead of letting the computation run to its end (and the exception
//! surface later, in whatever Python call came next).
//!
//! Signals are only handled on Python's main thread: polling happens on the thread that called
//! into the module (the solvers call their progress callbacks on the calling thread).

use pyo3::exceptions::{PyException, PyKeyboardInterrupt};
use pyo3::prelude::*;
use std::panic::AssertUnwindSafe;
use std::sync::Mutex;
use tvf_conformance::property_runner::StopRun;

/// The exception that stopped a computation, if one did.
#[derive(Default)]
pub struct Interruption {
    error: Mutex<Option<PyErr>>,
}

impl Interruption {
    /// Runs Python's pending signal handlers (with the GIL); if one raises (Ctrl+C:
    /// `KeyboardInterrupt`), stops the computation with that exception ([`Self::stop`]).
    pub fn poll(&self) {
        if let Some(error) = Python::attach(|py| py.check_signals().err()) {
            self.stop(error);
        }
    }

    /// Keeps `error` and unwinds with [`StopRun`] (no panic message: `resume_unwind` bypasses
    /// the panic hook); [`interruptible`] raises `error` once the computation has unwound.
    pub fn stop(&self, error: PyErr) -> ! {
        *self.error.lock().unwrap_or_else(|e| e.into_inner()) = Some(error);
        std::panic::resume_unwind(Box::new(StopRun))
    }

    /// `error` if it must stop the computation rather than be reported as its failure: an
    /// exception that is not an `Exception` (`KeyboardInterrupt`, `SystemExit`,
    /// `GeneratorExit`) stops it ([`Self::stop`]); an ordinary one is returned.
    pub fn unless_stopping(&self, py: Python<'_>, error: PyErr) -> PyErr {
        if error.is_instance_of::<PyException>(py) {
            return error;
        }
        self.stop(error)
    }

    fn take(&self) -> Option<PyErr> {
        self.error.lock().unwrap_or_else(|e| e.into_inner()).take()
    }
}

/// [`interruptible`] for a computation that does not poll: a signal that arrived meanwhile is
/// raised once it returns, before its result is turned into Python objects.
pub fn detached<T: Send>(py: Python<'_>, work: impl Send + FnOnce() -> T) -> PyResult<T> {
    interruptible(py, &Interruption::default(), work)
}

/// Runs `work` without the GIL. If it was stopped ([`Interruption::stop`]), raises the
/// exception that stopped it; any other panic goes on (PyO3 turns it into `PanicException`).
/// A signal that arrived while `work` ran without polling is handled once it returns, before
/// its result is turned into Python objects.
pub fn interruptible<T: Send>(
    py: Python<'_>,
    interruption: &Interruption,
    work: impl Send + FnOnce() -> T,
) -> PyResult<T> {
    match py.detach(|| std::panic::catch_unwind(AssertUnwindSafe(work))) {
        Ok(value) => {
            py.check_signals()?;
            Ok(value)
        }
        Err(payload) if payload.is::<StopRun>() => Err(interruption
            .take()
            .unwrap_or_else(|| PyKeyboardInterrupt::new_err("the computation was stopped"))),
        Err(payload) => std::panic::resume_unwind(payload),
    }
}
