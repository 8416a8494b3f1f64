//! The JSON constraint-set format: the documented example, round trips and every error, and a
//! set checked against a mesh and a complex.

use std::path::Path;
use tvf_core::generate::icosphere;
use tvf_core::SurfaceMesh;
use tvf_design::{
    Constraint, ConstraintAssembler, ConstraintError, ConstraintFileError, ConstraintSet, Location,
    OperatorFamily, Target,
};
use tvf_discretizations::{
    catalog_entry, Conforming, MassLumping, Nonconforming, DEFAULT_DISCRETIZATION,
};

fn example_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/constraints.json")
}

fn parse(text: &str) -> Result<ConstraintSet, ConstraintFileError> {
    ConstraintSet::parse(text, Path::new("set.json"))
}

fn error_of(constraint: &str) -> String {
    let text = format!("{{\"omega\": 0.1, \"constraints\": [{constraint}]}}");
    let error = parse(&text).expect_err("invalid constraint");
    error.to_string()
}

#[test]
fn the_documented_example_compiles_on_an_icosphere() {
    let set = ConstraintSet::load(example_path()).expect("example file");
    assert_eq!(set.omega, 0.1);
    assert_eq!(set.constraints.len(), 6);
    assert_eq!(set.constraints[2].weight, 10.0);
    assert_eq!(set.constraints[5].family, OperatorFamily::Other);
    assert_eq!(
        set.constraints[1].location,
        Location::Face {
            face: 30,
            barycentric: Some(vec![0.2, 0.3, 0.5])
        }
    );
    let mesh = icosphere(2);
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let compiled = ConstraintAssembler::new(&complex, &mesh)
        .compile_all(&set.constraints)
        .expect("fits the mesh");
    let rows: Vec<usize> = compiled.iter().map(|c| c.rows.len()).collect();
    assert_eq!(rows, vec![2, 2, 1, 1, 1, 1]);
    // The vector value is projected onto the face plane: |projection| ≤ |value|.
    let b = &compiled[1];
    assert!(b.values.iter().map(|v| v * v).sum::<f64>() <= 1.25 + 1e-12);
}

#[test]
fn the_issue_format_is_accepted_and_round_trips() {
    let text = r#"{"omega": 0.1, "constraints": [{"id": "a", "kind": "vector", "face": 12, "value": [1, 2, 3]},
      {"id": "b", "kind": "vector", "face": 30, "barycentric": [0.2, 0.3, 0.5], "value": [1, 0, 0]},
      {"id": "c", "kind": "divergence", "vertex": 5, "value": 2.0}, {"id": "d", "kind": "curl", "edge": 7, "value": -1.0},
      {"id": "e", "kind": "curl", "face": 3, "barycentric": [0.3, 0.3, 0.4], "value": 1.0}]}"#;
    let set = parse(text).expect("the issue's example");
    assert_eq!(set.constraints[3].target, Target::Curl(-1.0));
    assert_eq!(parse(&set.to_json()).unwrap(), set);
    let without_omega = parse(r#"{"constraints": []}"#).unwrap();
    assert_eq!(without_omega.omega, tvf_design::DEFAULT_OMEGA);
}

#[test]
fn parse_errors_name_the_file_and_the_constraint() {
    let cases = [
        (
            r#"{"id": "k", "kind": "swirl", "face": 1, "value": 1.0}"#,
            "unknown kind 'swirl'",
        ),
        (
            r#"{"id": "k", "kind": "vector", "face": -1, "value": [1, 0, 0]}"#,
            "face -1 is negative",
        ),
        (
            r#"{"id": "k", "kind": "curl", "face": 1, "barycentric": [0.5, 0.5, 0.5], "value": 1.0}"#,
            "sum to 1",
        ),
        (
            r#"{"id": "k", "kind": "curl", "face": 1, "barycentric": [1.5, -0.5, 0.0], "value": 1.0}"#,
            "non-negative",
        ),
        (
            r#"{"id": "k", "kind": "vector", "vertex": 1, "value": [1, 0, 0]}"#,
            "needs a \"face\"",
        ),
        (
            r#"{"id": "k", "kind": "vector", "face": 1, "value": 1.0}"#,
            "value [x, y, z]",
        ),
        (
            r#"{"id": "k", "kind": "curl", "face": 1, "edge": 2, "value": 1.0}"#,
            "exactly one",
        ),
        (
            r#"{"id": "k", "kind": "curl", "edge": 2, "value": 1.0, "weight": 0}"#,
            "weight must be finite and positive",
        ),
        (
            r#"{"id": "k", "kind": "curl", "edge": 2, "value": 1.0, "family": "mine"}"#,
            "unknown family",
        ),
        (
            r#"{"id": "k", "kind": "curl", "edge": 2, "value": 1.0}, {"id": "k", "kind": "curl", "edge": 3, "value": 1.0}"#,
            "used twice",
        ),
    ];
    for (constraint, expected) in cases {
        let message = error_of(constraint);
        assert!(message.starts_with("set.json: "), "{message}");
        assert!(message.contains("'k'"), "{message}");
        assert!(
            message.contains(expected),
            "expected '{expected}' in: {message}"
        );
    }
    let syntax = parse("{\"constraints\": [}").unwrap_err().to_string();
    assert!(
        syntax.starts_with("set.json: ") && syntax.contains("line 1"),
        "{syntax}"
    );
    let unknown_field =
        error_of(r#"{"id": "k", "kind": "curl", "edge": 2, "value": 1.0, "colour": 1}"#);
    assert!(unknown_field.contains("colour"), "{unknown_field}");
    let omega = parse(r#"{"omega": -1, "constraints": []}"#)
        .unwrap_err()
        .to_string();
    assert!(omega.contains("omega"), "{omega}");
    let missing = ConstraintSet::load("/nonexistent/c.json")
        .unwrap_err()
        .to_string();
    assert!(missing.contains("/nonexistent/c.json"), "{missing}");
}

#[test]
fn fingerprints_are_checked_when_present() {
    let set = parse(r#"{"mesh_fingerprint": "abc", "constraints": []}"#).unwrap();
    assert!(set.check_fingerprint("abc", Path::new("set.json")).is_ok());
    let error = set
        .check_fingerprint("xyz", Path::new("set.json"))
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("abc") && error.contains("xyz") && error.contains("set.json"),
        "{error}"
    );
    let unstamped = parse(r#"{"constraints": []}"#).unwrap();
    assert!(unstamped
        .check_fingerprint("anything", Path::new("set.json"))
        .is_ok());
}

#[test]
fn mesh_checks_and_node_kinds() {
    let mesh = icosphere(1);
    let conforming = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let assembler = ConstraintAssembler::new(&conforming, &mesh);
    let face = |f| Location::Face {
        face: f,
        barycentric: None,
    };
    let out_of_range = assembler.compile(&Constraint::new(
        "far",
        Target::Vector([1.0, 0.0, 0.0]),
        face(80),
    ));
    assert!(matches!(
        out_of_range,
        Err(ConstraintError::OutOfRange {
            what: "face",
            count: 80,
            ..
        })
    ));
    let vertex = assembler.compile(&Constraint::new(
        "v",
        Target::Divergence(1.0),
        Location::Vertex(42),
    ));
    assert!(matches!(
        vertex,
        Err(ConstraintError::OutOfRange { what: "vertex", .. })
    ));
    let nan = assembler.compile(&Constraint::new(
        "nan",
        Target::Curl(f64::NAN),
        Location::Edge(0),
    ));
    assert!(matches!(
        nan,
        Err(ConstraintError::NotFinite { what: "value", .. })
    ));
    // Conforming: curl lives on edges (CR); a vertex key needs the other family.
    let wrong = assembler
        .compile(&Constraint::new(
            "w",
            Target::Curl(1.0),
            Location::Vertex(3),
        ))
        .unwrap_err();
    assert!(matches!(wrong, ConstraintError::NodeKindMismatch { .. }));
    assert!(wrong.to_string().contains("\"edge\""), "{wrong}");
    assert!(
        wrong.to_string().contains("\"family\": \"other\""),
        "the conforming complex has the other family: {wrong}"
    );
    // DEC has no rotation, hence no other family: the advice does not offer it.
    let dec = tvf_discretizations::DecComplex::new(&mesh, MassLumping::Voronoi).unwrap();
    let on_edge = ConstraintAssembler::new(&dec, &mesh)
        .compile(&Constraint::new("e", Target::Curl(1.0), Location::Edge(3)))
        .unwrap_err();
    assert!(on_edge.to_string().contains("use \"face\""), "{on_edge}");
    assert!(!on_edge.to_string().contains("other"), "{on_edge}");
    let other = Constraint::new("w", Target::Curl(1.0), Location::Vertex(3))
        .with_family(OperatorFamily::Other);
    assert_eq!(assembler.compile(&other).unwrap().rows.len(), 1);
    // Nonconforming: divergence on edges, curl on vertices.
    let nonconforming = Nonconforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let swapped = ConstraintAssembler::new(&nonconforming, &mesh);
    assert!(swapped
        .compile(&Constraint::new(
            "d",
            Target::Divergence(1.0),
            Location::Edge(3)
        ))
        .is_ok());
    assert!(swapped
        .compile(&Constraint::new(
            "d",
            Target::Divergence(1.0),
            Location::Vertex(3)
        ))
        .is_err());
    assert!(swapped
        .compile(&Constraint::new(
            "c",
            Target::Curl(1.0),
            Location::Vertex(3)
        ))
        .is_ok());
    // A point value is the interpolation-weighted mix of nodal rows: at a corner it is the node's row.
    let corner = mesh.faces()[5][1];
    let at_corner = Location::Face {
        face: 5,
        barycentric: Some(vec![0.0, 1.0, 0.0]),
    };
    let point = assembler
        .compile(&Constraint::new("p", Target::Divergence(1.0), at_corner))
        .unwrap();
    let node = assembler
        .compile(&Constraint::new(
            "n",
            Target::Divergence(1.0),
            Location::Vertex(corner),
        ))
        .unwrap();
    assert_eq!(point.rows, node.rows);
}

#[test]
fn a_constraint_out_of_range_or_of_another_mesh_is_refused_naming_the_file() {
    let mesh = SurfaceMesh::from(icosphere(1));
    let complex = catalog_entry(DEFAULT_DISCRETIZATION)
        .unwrap()
        .build(&mesh)
        .unwrap();
    let origin = Path::new("c.json");
    let check = |text: &str| {
        let set = ConstraintSet::parse(text, origin).unwrap();
        set.check_for(origin, &mesh, complex.as_ref())
    };
    let good = r#"{"constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]}]}"#;
    assert!(check(good).is_ok());
    let far = r#"{"constraints": [{"id": "b", "kind": "divergence", "vertex": 9999, "value": 1}]}"#;
    let error = check(far).unwrap_err();
    assert!(
        matches!(error, ConstraintFileError::Invalid { .. }),
        "{error}"
    );
    let text = error.to_string();
    assert!(text.starts_with("c.json: constraint 'b'"), "{text}");
    let other = r#"{"mesh_fingerprint": "0000000000000001", "constraints": []}"#;
    let error = check(other).unwrap_err();
    assert!(
        matches!(error, ConstraintFileError::FingerprintMismatch { .. }),
        "{error}"
    );
}
