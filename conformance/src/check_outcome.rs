//! [`CheckOutcome`]: what one conformance check measured and whether that passes. The core checks
//! measure first ([`crate::algebra_checks::measure_d1_d0_zero`] and the other `measure_*`
//! functions) and the suite asserts on the outcomes ([`assert_outcomes`]); [`crate::check_report`]
//! returns them instead, for callers that want a report (the Python package's `tvf.check`).

use serde::Serialize;

/// Whether a check passed, failed or was not run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CheckStatus {
    /// The measured value is within the limit.
    Passed,
    /// The measured value exceeds the limit (or a count differs from the expected one).
    Failed,
    /// Not run (a dense check on a complex too large for it).
    Skipped,
    /// Cannot run on this complex: it lacks what the check needs (a capability, a builder for
    /// other meshes, nodes where a linear function has values); the detail says what.
    NotApplicable,
}

impl CheckStatus {
    /// Lower-case name: `passed`, `failed`, `skipped`, `not applicable`.
    pub fn name(self) -> &'static str {
        match self {
            CheckStatus::Passed => "passed",
            CheckStatus::Failed => "failed",
            CheckStatus::Skipped => "skipped",
            CheckStatus::NotApplicable => "not applicable",
        }
    }
}

/// How a check's measured value is compared with its limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Comparison {
    /// Passes when `measured ≤ limit` (an error norm against its tolerance).
    AtMost,
    /// Passes when `measured = limit` (a count against the expected count).
    Equals,
    /// Passes when `measured ≥ limit` (an observed order of convergence against the least
    /// order accepted).
    AtLeast,
}

impl Comparison {
    /// Lower-case name, as in JSON: `at_most`, `equals`, `at_least`.
    pub fn name(self) -> &'static str {
        match self {
            Comparison::AtMost => "at_most",
            Comparison::Equals => "equals",
            Comparison::AtLeast => "at_least",
        }
    }

    /// The sign between the measured value and the limit: `≤`, `=` or `≥`.
    pub fn symbol(self) -> &'static str {
        match self {
            Comparison::AtMost => "≤",
            Comparison::Equals => "=",
            Comparison::AtLeast => "≥",
        }
    }
}

/// A status by its name.
fn status_name<S: serde::Serializer>(
    status: &CheckStatus,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(status.name())
}

/// One measured property of a complex; serialized with the keys of its fields, the status by
/// its name, a measurement or limit that is not finite as `null` by `serde_json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckOutcome {
    /// Stable name of the check, e.g. `d1_d0_zero` or `symmetric:S`.
    pub name: String,
    /// The outcome.
    #[serde(serialize_with = "status_name")]
    pub status: CheckStatus,
    /// The measured value (an error norm, or a count for counting checks).
    pub measured: f64,
    /// The largest value that passes (for counting checks: the expected count).
    pub limit: f64,
    /// How `measured` is compared with `limit`; serialized as `at_most` or `equals`.
    pub comparison: Comparison,
    /// One line saying what was measured against what.
    pub detail: String,
}

impl CheckOutcome {
    /// Passes when `measured ≤ limit` (a NaN measurement fails).
    pub fn at_most(name: impl Into<String>, measured: f64, limit: f64, detail: String) -> Self {
        let passed = measured <= limit;
        Self::new(name, passed, measured, limit, detail).compared(Comparison::AtMost)
    }

    /// Passes when the count `measured` equals `expected`.
    pub fn count(
        name: impl Into<String>,
        measured: usize,
        expected: usize,
        detail: String,
    ) -> Self {
        Self::new(
            name,
            measured == expected,
            measured as f64,
            expected as f64,
            detail,
        )
        .compared(Comparison::Equals)
    }

    /// Passes when `measured ≥ limit` (a NaN measurement fails).
    pub fn at_least(name: impl Into<String>, measured: f64, limit: f64, detail: String) -> Self {
        let passed = measured >= limit;
        Self::new(name, passed, measured, limit, detail).compared(Comparison::AtLeast)
    }

    /// A check that cannot run on this complex; `reason` says what it lacks.
    pub fn not_applicable(name: impl Into<String>, reason: String) -> Self {
        Self {
            status: CheckStatus::NotApplicable,
            ..Self::skipped(name, reason)
        }
    }

    /// A check that failed before it could measure anything (e.g. a factorization failed).
    pub fn failed(name: impl Into<String>, detail: String) -> Self {
        Self::new(name, false, f64::NAN, f64::NAN, detail)
    }

    /// A check not run; `reason` says why.
    pub fn skipped(name: impl Into<String>, reason: String) -> Self {
        Self {
            name: name.into(),
            status: CheckStatus::Skipped,
            measured: f64::NAN,
            limit: f64::NAN,
            comparison: Comparison::AtMost,
            detail: reason,
        }
    }

    fn new(
        name: impl Into<String>,
        passed: bool,
        measured: f64,
        limit: f64,
        detail: String,
    ) -> Self {
        Self {
            name: name.into(),
            status: if passed {
                CheckStatus::Passed
            } else {
                CheckStatus::Failed
            },
            measured,
            limit,
            comparison: Comparison::AtMost,
            detail,
        }
    }

    fn compared(self, comparison: Comparison) -> Self {
        Self { comparison, ..self }
    }

    /// Whether the check failed.
    pub fn failed_check(&self) -> bool {
        self.status == CheckStatus::Failed
    }
}

/// Panics with the name and detail of every failed outcome (the suite's assertion).
pub fn assert_outcomes(outcomes: &[CheckOutcome]) {
    let failures: Vec<String> = outcomes
        .iter()
        .filter(|o| o.failed_check())
        .map(|o| format!("{}: {}", o.name, o.detail))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("; "));
}
