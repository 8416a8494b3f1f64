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

/// `TvfError` whose message is `error` and its sources, joined by `: ` (causes already contained
/// in the message are skipped, as the command line does).
pub fn from_error(error: &(dyn Error + 'static)) -> PyErr {
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
    tvf_error(message)
}

/// `TvfError` with `context: error`.
pub fn with_context(context: &str, error: &(dyn Error + 'static)) -> PyErr {
    let inner = from_error(error);
    pyo3::Python::attach(|py| tvf_error(format!("{context}: {}", inner.value(py))))
}
