//! `tvf.TvfError` and the conversion of Rust errors into it, worded as the command line words
//! them (the error and its causes joined by `: `).

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::PyErr;
use std::error::Error;

create_exception!(
    tvf,
    TvfError,
    PyValueError,
    "Bad input or a failed computation; the message is the one the tvf command line prints."
);

/// `TvfError` with `message`.
pub fn tvf_error(message: impl Into<String>) -> PyErr {
    TvfError::new_err(message.into())
}

/// `error` and its sources joined by `: `, skipping causes the message already contains (as
/// the command line prints an error).
fn chain(error: &(dyn Error + 'static)) -> String {
    let mut message = String::new();
    let mut cause = Some(error);
    while let Some(e) = cause {
        let text = e.to_string();
        if !message.contains(&text) {
            if !message.is_empty() {
                message.push_str(": ");
            }
            message.push_str(&text);
        }
        cause = e.source();
    }
    message
}

/// `TvfError` whose message is `error` and its causes.
pub fn from_error(error: &(dyn Error + 'static)) -> PyErr {
    tvf_error(chain(error))
}

/// `TvfError` with `context: error` (and its causes).
pub fn with_context(context: &str, error: &(dyn Error + 'static)) -> PyErr {
    tvf_error(format!("{context}: {}", chain(error)))
}
