//! The reports of design solves: the residual list with its worst entry, the timed reduced and
//! full solves (their lines, JSON keys and accuracy notes), orderings by name, and the checks
//! that refuse non-finite or overflowing residuals naming the constraint.

use tvf_core::discretization::HodgeOperators;
use tvf_core::generate::icosphere;
use tvf_design::{
    checked_residuals, parse_fill_ordering, timed_full_design, worst_residual, CompiledConstraint,
    Constraint, ConstraintAssembler, ConstraintResidual, FactorParallelism, FillOrdering, Location,
    ResidualReport, RowOrigin, Target, TimedFullDesign, TimedReducedSolve,
};
use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};

#[test]
fn residuals_are_listed_with_the_worst_one() {
    let r = |id: &str, relative| ConstraintResidual {
        id: id.into(),
        absolute: 2.0 * relative,
        relative,
    };
    let report = ResidualReport::new(vec![r("east", 1e-3), r("source", 2e-2)]);
    assert_eq!(report.worst_relative_residual, 2e-2);
    let lines = report.lines();
    assert_eq!(lines.len(), 4);
    assert_eq!(lines[1], "  east             2.000e-3  1.000e-3");
    assert_eq!(lines[3], "worst relative residual 2.000e-2");
    let keys = serde_json::to_value(&report).unwrap();
    assert_eq!(keys["residuals"][1]["id"], "source");
    assert_eq!(keys["residuals"][1]["absolute"], 4e-2);
    assert_eq!(ResidualReport::new(Vec::new()).worst_relative_residual, 0.0);
}

#[test]
fn reduced_solves_report_their_steps() {
    let solved = TimedReducedSolve {
        field: vec![1.0],
        rows: 3,
        setup_ms: 1.0,
        solve_ms: 2.0,
        map_ms: 0.5,
    };
    assert_eq!(
        solved.spline_lines(2, 10)[0],
        "spline setup    1.000 ms (2 constraints, 3 rows, d = 10)"
    );
    let keys = serde_json::to_value(&solved).unwrap();
    assert_eq!(
        keys,
        serde_json::json!({"rows": 3, "setup_ms": 1.0, "solve_ms": 2.0, "map_ms": 0.5})
    );
    assert_eq!(
        solved.reduced_design_lines(10)[1],
        "reduced solve   2.000 ms + 0.500 ms mapping to the full field"
    );
    let keys = serde_json::to_value(solved.reduced_design_times()).unwrap();
    assert_eq!(keys["solver"], "reduced");
    assert_eq!(keys["factor_ms"], 1.0);
}

#[test]
fn a_full_design_is_timed_reported_and_accurate() {
    let mesh = tvf_core::SurfaceMesh::from(icosphere(1));
    let entry = catalog_entry(DEFAULT_DISCRETIZATION).unwrap();
    let complex = entry.build(&mesh).unwrap();
    let source = Constraint::new("source", Target::Divergence(2.0), Location::Vertex(5));
    let compiled = ConstraintAssembler::new(complex.as_ref(), &mesh)
        .compile_all(&[source])
        .unwrap();
    let solved = timed_full_design(
        complex.as_ref(),
        0.1,
        compiled,
        FillOrdering::Amd,
        FactorParallelism::default(),
    )
    .unwrap();
    assert_eq!(solved.field.len(), complex.field_dimension());
    assert_eq!(solved.ordering, "amd");
    assert!(solved.factor_entries > 0 && !solved.system_residuals.is_empty());
    assert_eq!(solved.accuracy_note(), Ok(None));
    let lines = solved.lines();
    assert!(lines[1].contains("amd ordering"), "{lines:?}");
    assert!(lines[3].starts_with("system residual"), "{lines:?}");
    let keys = serde_json::to_value(&solved).unwrap();
    assert_eq!(keys["solver"], "full");
    assert!(keys.get("field").is_none() && keys.get("factorization_ms").is_none());
}

#[test]
fn a_solve_at_the_rounding_floor_gets_a_note_and_one_above_it_an_error() {
    let mut solved = TimedFullDesign {
        field: vec![0.0],
        solver: "full",
        assembly_ms: 0.0,
        factor_ms: 0.0,
        solve_ms: 0.0,
        ordering: "nd",
        factor_entries: 1,
        factor_gflop: 0.0,
        system_residuals: vec![1e-3, 5e-8],
        rounding_floor: 1e-8,
        system_assembly_ms: 0.0,
        factorization_ms: 0.0,
    };
    let note = solved.accuracy_note().unwrap().expect("a note");
    assert!(note.contains("5.0e-8") && note.contains("1.0e-8"), "{note}");
    solved.rounding_floor = 1e-12;
    assert_eq!(solved.accuracy_note().unwrap_err().final_residual(), 5e-8);
}

#[test]
fn orderings_parse_by_name() {
    assert_eq!(
        parse_fill_ordering("metis"),
        Ok(FillOrdering::NestedDissection)
    );
    assert!(parse_fill_ordering("foo")
        .unwrap_err()
        .contains("amd or nd"));
}

fn constraint(id: &str, values: Vec<f64>) -> CompiledConstraint {
    CompiledConstraint {
        id: id.into(),
        rows: values
            .iter()
            .enumerate()
            .map(|(k, _)| vec![(k, 1.0)])
            .collect(),
        origins: vec![RowOrigin::Field; values.len()],
        values,
        weight: 1.0,
    }
}

#[test]
fn the_worst_residual_counts_nan_as_worst() {
    let r = |id: &str, relative| ConstraintResidual {
        id: id.into(),
        absolute: relative,
        relative,
    };
    let residuals = [r("a", 1e-3), r("b", f64::NAN), r("c", 1e-1)];
    assert_eq!(worst_residual(&residuals).map(|r| r.id.as_str()), Some("b"));
    assert!(worst_residual(&[]).is_none());
}

#[test]
fn a_nan_field_names_the_constraint_with_the_largest_values() {
    let constraints = [
        constraint("small", vec![1.0]),
        constraint("huge", vec![1e308, -1e308]),
    ];
    let error = checked_residuals(&[f64::NAN, 0.0], &constraints, 0.1).unwrap_err();
    let text = error.to_string();
    assert!(text.contains("'huge'") && text.contains("NaN"), "{text}");
}

#[test]
fn an_overflowing_residual_is_an_error_and_a_finite_one_is_not() {
    let constraints = [constraint("big", vec![1e200, 1e200])];
    let error = checked_residuals(&[-1e200, -1e200], &constraints, 0.1).unwrap_err();
    assert!(error.to_string().contains("'big'"), "{error}");
    let fine = checked_residuals(&[1.0, 2.0], &[constraint("ok", vec![1.0, 2.0])], 0.1);
    assert_eq!(fine.map(|r| r[0].absolute), Ok(0.0));
}
