//! What a check run reports (`tvf check`): the outcomes of the checks on one mesh
//! ([`MeshCheckReport`]) or of a property run on generated meshes with its minimal failing mesh
//! ([`PropertyRunReport`]), as aligned text lines and as JSON keys (each report serializes as
//! one JSON object).

use crate::check_outcome::CheckOutcome;
use crate::check_report::CheckReport;
use crate::property_runner::{PropertyReport, PropertyRequest};
use crate::reference_report::catalog_reference_checks;
use crate::strategies::MeshNeeds;
use serde::Serialize;
use std::path::Path;
use tvf_core::mesh::Mesh;
use tvf_discretizations::CatalogEntry;

/// The checks of one discretization on one mesh. Serialized as `discretization`, `passed`,
/// `checks` (one object per check: `name`, `status`, `measured`, `limit`, `detail`) and
/// `failed` (the names of the failed checks).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeshCheckReport {
    /// What was checked: a catalog id, or a description of the matrices.
    pub discretization: String,
    /// Whether no check failed.
    pub passed: bool,
    /// Every outcome.
    pub checks: Vec<CheckOutcome>,
    /// The names of the failed checks.
    pub failed: Vec<String>,
    /// How the mesh is named (its file, or `example:NAME`).
    #[serde(skip)]
    pub mesh: String,
    /// Faces of the mesh.
    #[serde(skip)]
    pub faces: usize,
}

impl MeshCheckReport {
    /// The report of `checked`, the checks of `discretization` on the mesh called `mesh` with
    /// `faces` faces.
    pub fn new(discretization: &str, mesh: &str, faces: usize, checked: CheckReport) -> Self {
        Self {
            discretization: discretization.to_string(),
            passed: checked.passed(),
            failed: failure_names(&checked),
            checks: checked.outcomes,
            mesh: mesh.to_string(),
            faces,
        }
    }

    /// The verdict, then one line per check ([`outcome_lines`]).
    pub fn lines(&self) -> Vec<String> {
        let mut lines = vec![format!(
            "{} on {} ({} faces): {}",
            self.discretization,
            self.mesh,
            self.faces,
            verdict(self.passed)
        )];
        lines.extend(outcome_lines(&self.checks));
        lines
    }

    /// `failed checks: NAME, ...` if a check failed.
    pub fn failure_message(&self) -> Option<String> {
        failure_message(&self.failed)
    }
}

/// A property run of one catalog entry on generated meshes. Serialized as `discretization`,
/// `cases`, `seed`, `cases_passed`, `passed`, `checks` (each check's worst case over the
/// passing meshes) and, when a case failed, `counterexample` ([`CounterexampleReport`]) and
/// `failed` (the names of the checks the counterexample fails).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PropertyRunReport {
    /// The catalog id.
    pub discretization: String,
    /// Meshes asked for.
    pub cases: u32,
    /// Seed of the generated meshes.
    pub seed: u64,
    /// Meshes checked before the first failure.
    pub cases_passed: u32,
    /// Whether every case passed.
    pub passed: bool,
    /// Per check, its worst outcome over the passing meshes.
    pub checks: Vec<CheckOutcome>,
    /// The minimal failing mesh, if a case failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub counterexample: Option<CounterexampleReport>,
    /// The checks the minimal failing mesh fails (present with it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failed: Option<Vec<String>>,
    /// Why the run stopped without a counterexample, if it did.
    #[serde(skip)]
    pub aborted: Option<String>,
    /// The accuracy checks ([`crate::accuracy`]), run once besides the generated meshes (empty
    /// when not run; serialized only when run).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub accuracy: Vec<CheckOutcome>,
}

/// The minimal failing mesh of a property run, written as OBJ. Serialized as `path`, `faces`,
/// `description`, `reproduce`, `checks` and `reproduced`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CounterexampleReport {
    /// Where the mesh is written.
    pub path: String,
    /// Faces of the mesh.
    pub faces: usize,
    /// The mesh's description (what the generator drew).
    pub description: String,
    /// The command line that checks the written mesh again.
    pub reproduce: String,
    /// Every outcome on the mesh, as measured in the run that failed.
    pub checks: Vec<CheckOutcome>,
    /// Whether checking the mesh once more failed again (`false`: a non-deterministic failure,
    /// the builder's or a check's result changes from call to call).
    pub reproduced: bool,
}

impl PropertyRunReport {
    /// The report of the property run `outcome` of `request` for the catalog entry
    /// `discretization`, its minimal failing mesh (if any) to be written to `counterexample`
    /// and checked again by the command line program `program` (`tvf`, or a program of your own
    /// with its own catalog).
    pub fn new<Spec, M: Mesh>(
        program: &str,
        discretization: &str,
        request: &PropertyRequest,
        outcome: &PropertyReport<Spec, M>,
        counterexample: &Path,
    ) -> Self {
        let failing = outcome.counterexample.as_ref();
        Self {
            discretization: discretization.to_string(),
            cases: request.cases,
            seed: request.seed,
            cases_passed: outcome.cases_passed,
            passed: outcome.passed(),
            checks: outcome.worst.clone(),
            counterexample: failing.map(|failing| CounterexampleReport {
                path: counterexample.display().to_string(),
                faces: failing.mesh.mesh.face_count(),
                description: failing.mesh.name.clone(),
                reproduce: format!(
                    "{program} check {} --discretization {discretization}",
                    counterexample.display()
                ),
                checks: failing.report.outcomes.clone(),
                reproduced: failing.reproduced,
            }),
            failed: failing.map(|failing| failure_names(&failing.report)),
            aborted: outcome.aborted.clone(),
            accuracy: Vec::new(),
        }
    }

    /// The report with the accuracy checks `accuracy` added: a failed one fails the run and is
    /// named among `failed`.
    pub fn with_accuracy(mut self, accuracy: Vec<CheckOutcome>) -> Self {
        let failed: Vec<String> = accuracy
            .iter()
            .filter(|o| o.failed_check())
            .map(|o| o.name.clone())
            .collect();
        if !failed.is_empty() {
            self.passed = false;
            self.failed.get_or_insert_with(Vec::new).extend(failed);
        }
        self.accuracy = accuracy;
        self
    }

    /// The accuracy checks' heading and one line per check; none when they did not run.
    pub fn accuracy_lines(&self) -> Vec<String> {
        if self.accuracy.is_empty() {
            return Vec::new();
        }
        let mut lines = vec![format!(
            "accuracy checks (consistency on patches, convergence on the sphere and hemisphere): {}",
            verdict(!self.accuracy.iter().any(CheckOutcome::failed_check))
        )];
        lines.extend(outcome_lines(&self.accuracy));
        lines
    }

    /// The verdict, then (unless the run was aborted) each check's worst case.
    pub fn lines(&self) -> Vec<String> {
        let mut lines = vec![format!(
            "{} on {} generated meshes (seed {}): {}",
            self.discretization,
            self.cases,
            self.seed,
            verdict(self.passed)
        )];
        if self.aborted.is_none() {
            lines.push(format!(
                "worst case of each check over the {} passing meshes:",
                self.cases_passed
            ));
            lines.extend(outcome_lines(&self.checks));
        }
        lines.extend(self.accuracy_lines());
        lines
    }

    /// Where the minimal failing mesh was written and how to check it again, then one line
    /// per check on it; none without a counterexample.
    pub fn counterexample_lines(&self) -> Vec<String> {
        let Some(counterexample) = &self.counterexample else {
            return Vec::new();
        };
        let mut lines = vec![
            format!(
                "minimal failing mesh ({} faces): {}",
                counterexample.faces, counterexample.description
            ),
            format!(
                "  written to {}; reproduce with: {}",
                counterexample.path, counterexample.reproduce
            ),
        ];
        if !counterexample.reproduced {
            lines.push(
                "  non-deterministic: checked once more, this mesh passed; the failure below is \
                 from the run that failed (a builder or check whose result changes from call to \
                 call)"
                    .to_string(),
            );
        }
        lines.extend(outcome_lines(&counterexample.checks));
        lines
    }

    /// How many generated meshes passed, for the end of a progress bar: `N of N meshes passed`,
    /// or, after a failure, `K meshes passed, mesh K+1 of N failed` (a run stops at its first
    /// failing mesh and shrinks it).
    pub fn cases_summary(&self) -> String {
        if self.counterexample.is_some() {
            let plural = if self.cases_passed == 1 { "" } else { "es" };
            format!(
                "{} mesh{plural} passed, mesh {} of {} failed",
                self.cases_passed,
                self.cases_passed + 1,
                self.cases
            )
        } else {
            format!("{} of {} meshes passed", self.cases_passed, self.cases)
        }
    }

    /// `the property run stopped: REASON` if the run was aborted.
    pub fn abort_message(&self) -> Option<String> {
        let reason = self.aborted.as_ref()?;
        Some(format!("the property run stopped: {reason}"))
    }

    /// `failed checks: NAME, ...` if the minimal failing mesh fails checks.
    pub fn failure_message(&self) -> Option<String> {
        failure_message(self.failed.as_deref().unwrap_or_default())
    }
}

/// The property run of `cases` meshes drawn with `seed` for the catalog `entry`: Delaunay meshes
/// if it needs them, with its measured reference checks.
pub fn entry_property_request(entry: &CatalogEntry, cases: u32, seed: u64) -> PropertyRequest {
    let mut request = PropertyRequest::new(cases, seed, MeshNeeds::default());
    request.needs.delaunay = entry.needs_delaunay();
    request.reference = catalog_reference_checks(entry.id()).to_vec();
    request
}

/// One aligned line per check: status, name, measured value against its limit (`-` when not
/// finite; `≤`, or `=` for counts), detail.
pub fn outcome_lines(outcomes: &[CheckOutcome]) -> Vec<String> {
    outcomes
        .iter()
        .map(|o| {
            format!(
                "  {:<7} {:<48} {:>11} {} {:<11} {}",
                o.status.name(),
                o.name,
                number(o.measured),
                o.comparison.symbol(),
                number(o.limit),
                o.detail
            )
        })
        .collect()
}

/// `passed` or `FAILED`.
pub fn verdict(passed: bool) -> &'static str {
    if passed {
        "passed"
    } else {
        "FAILED"
    }
}

fn failure_names(checked: &CheckReport) -> Vec<String> {
    checked.failures().iter().map(|o| o.name.clone()).collect()
}

fn failure_message(failed: &[String]) -> Option<String> {
    (!failed.is_empty()).then(|| format!("failed checks: {}", failed.join(", ")))
}

fn number(x: f64) -> String {
    if x.is_nan() {
        "-".to_string()
    } else {
        format!("{x:.3e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::property_runner::Counterexample;
    use crate::strategies::{ClosedShape, Jitter, MeshSpec, Shape};

    fn outcomes() -> Vec<CheckOutcome> {
        vec![
            CheckOutcome::at_most("d1_d0_zero", 1e-14, 1e-12, "‖d1 d0‖".into()),
            CheckOutcome::failed("construction", "refused".into()),
        ]
    }

    #[test]
    fn outcomes_are_aligned_with_a_dash_for_nan() {
        let lines = outcome_lines(&outcomes());
        assert_eq!(
            lines[0],
            format!(
                "  passed  {:<48}   1.000e-14 ≤ 1.000e-12   ‖d1 d0‖",
                "d1_d0_zero"
            )
        );
        assert!(
            lines[1].contains("          - ≤ -           refused"),
            "{}",
            lines[1]
        );
    }

    #[test]
    fn a_count_is_shown_and_serialized_as_an_equality() {
        let count = CheckOutcome::count("kernel dimension", 2, 2, "dim ker L".into());
        let line = &outcome_lines(std::slice::from_ref(&count))[0];
        assert!(line.contains("2.000e0 = 2.000e0"), "{line}");
        let json = serde_json::to_value(&count).unwrap();
        assert_eq!(json["comparison"], "equals");
        let bound = serde_json::to_value(&outcomes()[0]).unwrap();
        assert_eq!(bound["comparison"], "at_most");
    }

    #[test]
    fn a_mesh_check_names_its_failures() {
        let checked = CheckReport {
            outcomes: outcomes(),
        };
        let report = MeshCheckReport::new("mine", "m.obj", 12, checked);
        assert_eq!(report.lines()[0], "mine on m.obj (12 faces): FAILED");
        assert_eq!(
            report.failure_message().as_deref(),
            Some("failed checks: construction")
        );
        let keys = serde_json::to_value(&report).unwrap();
        assert_eq!(keys["failed"], serde_json::json!(["construction"]));
        assert_eq!(keys["checks"][0]["status"], "passed");
        assert!(keys.get("faces").is_none());
    }

    #[test]
    fn a_property_run_reports_its_counterexample() {
        let spec = MeshSpec {
            components: vec![Shape::Closed(ClosedShape::Sphere { level: 0 })],
            jitter: Jitter {
                amplitude: 0.0,
                seed: 0,
            },
            delaunay: false,
            motion: None,
        };
        let mut mesh = spec.build().unwrap();
        mesh.name = "tiny".into();
        let failing = Counterexample {
            spec,
            mesh,
            report: CheckReport {
                outcomes: outcomes(),
            },
            reproduced: false,
        };
        let outcome = PropertyReport {
            cases_passed: 3,
            worst: outcomes()[..1].to_vec(),
            counterexample: Some(failing),
            aborted: None,
        };
        let request = PropertyRequest::new(8, 1, MeshNeeds::default());
        let report = PropertyRunReport::new(
            "tvf-example-own-discretization",
            "mine",
            &request,
            &outcome,
            Path::new("ce.obj"),
        );
        assert_eq!(
            report.cases_summary(),
            "3 meshes passed, mesh 4 of 8 failed"
        );
        let lines = report.lines();
        assert_eq!(lines[0], "mine on 8 generated meshes (seed 1): FAILED");
        assert_eq!(lines.len(), 3);
        let counterexample = report.counterexample_lines();
        assert_eq!(counterexample[0], "minimal failing mesh (20 faces): tiny");
        assert!(counterexample[1]
            .ends_with("tvf-example-own-discretization check ce.obj --discretization mine"));
        assert!(
            counterexample[2].contains("non-deterministic"),
            "{counterexample:?}"
        );
        let keys = serde_json::to_value(&report).unwrap();
        assert_eq!(keys["counterexample"]["faces"], 20);
        assert_eq!(keys["counterexample"]["reproduced"], false);
        assert_eq!(keys["failed"], serde_json::json!(["construction"]));
        assert!(report.abort_message().is_none());
        let passing = PropertyReport {
            counterexample: None,
            ..outcome
        };
        let report = PropertyRunReport::new("tvf", "mine", &request, &passing, Path::new("ce.obj"));
        assert_eq!(report.cases_summary(), "3 of 8 meshes passed");
        let keys = serde_json::to_value(&report).unwrap();
        assert!(keys.get("failed").is_none() && keys.get("counterexample").is_none());
        assert!(keys.get("accuracy").is_none());
        assert!(report.counterexample_lines().is_empty() && report.failure_message().is_none());
        let order = CheckOutcome::at_least("convergence:sphere:integrable", 0.1, 1.5, "t".into());
        let report = report.with_accuracy(vec![order]);
        assert!(!report.passed);
        assert_eq!(
            report.failure_message().as_deref(),
            Some("failed checks: convergence:sphere:integrable")
        );
        let keys = serde_json::to_value(&report).unwrap();
        assert_eq!(keys["accuracy"][0]["comparison"], "at_least");
        assert!(report
            .lines()
            .iter()
            .any(|l| l.contains("0.1") || l.contains("1.000e-1")));
    }

    #[test]
    fn an_aborted_run_says_why_and_lists_no_worst_cases() {
        let outcome: PropertyReport = PropertyReport {
            cases_passed: 0,
            worst: outcomes(),
            counterexample: None,
            aborted: Some("too many rejects".into()),
        };
        let request = PropertyRequest::new(4, 0, MeshNeeds::default());
        let report = PropertyRunReport::new("tvf", "mine", &request, &outcome, Path::new("x.obj"));
        assert_eq!(report.lines().len(), 1);
        assert_eq!(
            report.abort_message().as_deref(),
            Some("the property run stopped: too many rejects")
        );
    }
}
