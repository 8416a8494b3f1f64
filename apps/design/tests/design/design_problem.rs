//! A design problem from a mesh and a constraint file: its summary, the spline and reduced
//! design through it with their residuals, and errors that name the constraint file.

use tvf_core::discretization::HodgeOperators;
use tvf_core::generate::icosphere;
use tvf_design::{ConstraintFileError, DesignProblem, DesignRunError, ReducedBasis};
use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};
use tvf_spectral::{compute_basis, BasisRequest};

const CONSTRAINTS: &str = r#"{"omega": 0.1, "constraints": [
  {"id": "east", "kind": "vector", "face": 12, "value": [1, 0, 0]},
  {"id": "source", "kind": "divergence", "vertex": 5, "value": 2.0}]}"#;

fn problem(
    text: &str,
) -> (
    tempfile::TempDir,
    Result<DesignProblem, ConstraintFileError>,
) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("c.json");
    std::fs::write(&path, text).unwrap();
    let loaded = DesignProblem::load(icosphere(1).into(), "example:ico", &path);
    (dir, loaded)
}

#[test]
fn a_problem_is_summarized_solved_and_checked() {
    let (_dir, problem) = problem(CONSTRAINTS);
    let problem = problem.unwrap();
    let summary = problem.summary();
    assert_eq!(
        (summary.faces, summary.genus, summary.constraints),
        (80, 0, 2)
    );
    assert!(summary.lines()[1].starts_with("constraints     2 from "));
    let entry = catalog_entry(DEFAULT_DISCRETIZATION).unwrap();
    let complex = entry.build(&problem.mesh).unwrap();
    let constraints = problem.compile(complex.as_ref()).unwrap();
    let basis = compute_basis(complex.as_ref(), &BasisRequest::pairs(20)).unwrap();
    let basis = ReducedBasis::from_spectral(&basis).unwrap();
    let spline = problem.spline(&basis, &constraints).unwrap();
    let report = problem.residuals(&spline.field, &constraints).unwrap();
    assert!(report.worst_relative_residual < 1e-9, "{report:?}");
    let design = problem
        .reduced_design(complex.as_ref(), &basis, &constraints)
        .unwrap();
    assert_eq!(design.field.len(), complex.field_dimension());
    let nan = vec![f64::NAN; complex.field_dimension()];
    let error = problem.residuals(&nan, &constraints).unwrap_err();
    assert!(matches!(error, DesignRunError::Solve { .. }), "{error}");
}

#[test]
fn errors_name_the_constraint_file() {
    let (_dir, problem) = problem(&CONSTRAINTS.replace("\"face\": 12", "\"face\": 999"));
    let problem = problem.unwrap();
    let entry = catalog_entry(DEFAULT_DISCRETIZATION).unwrap();
    let complex = entry.build(&problem.mesh).unwrap();
    let error = problem.compile(complex.as_ref()).unwrap_err();
    assert!(error.to_string().ends_with("c.json"), "{error}");
    let source = std::error::Error::source(&error).unwrap().to_string();
    assert!(source.contains("face 999 is out of range"), "{source}");
    let (_dir, other) = problem_with_fingerprint("0000000000000000");
    assert!(matches!(
        other.unwrap_err(),
        ConstraintFileError::FingerprintMismatch { .. }
    ));
}

fn problem_with_fingerprint(
    fingerprint: &str,
) -> (
    tempfile::TempDir,
    Result<DesignProblem, ConstraintFileError>,
) {
    problem(&CONSTRAINTS.replacen(
        "{\"omega\"",
        &format!("{{\"mesh_fingerprint\": \"{fingerprint}\", \"omega\""),
        1,
    ))
}
