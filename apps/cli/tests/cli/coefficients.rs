//! End-to-end: `tvf coefficients` recovers the coefficients of a known combination of basis
//! fields and refuses a basis of another mesh.

use crate::common::{assert_success, tvf};
use tvf_core::discretization::FieldSampling;
use tvf_core::generate::{genus_surface, torus};
use tvf_core::io::{load_mesh, write_obj};
use tvf_discretizations::FaceFields;
use tvf_spectral::{open_basis_file, write_face_vectors};

#[test]
fn coefficients_of_a_combination_of_basis_fields() {
    let dir = tempfile::tempdir().unwrap();
    let mesh_path = dir.path().join("genus1.obj");
    write_obj(&mesh_path, &genus_surface(1, 4)).unwrap();
    let basis_path = dir.path().join("b.tvfb");
    let status = tvf()
        .arg("basis")
        .arg(&mesh_path)
        .args(["-k", "18", "--quiet", "-o"])
        .arg(&basis_path)
        .status()
        .unwrap();
    assert!(status.success());
    let mesh = load_mesh(&mesh_path)
        .unwrap()
        .mesh
        .into_triangles()
        .unwrap();
    let (_, basis) = open_basis_file(
        tvf_discretizations::builtin_catalog(),
        &basis_path,
        &mesh,
        None,
        None,
    )
    .unwrap();
    let space = FaceFields::new(&mesh).unwrap();
    let wanted: Vec<f64> = (0..basis.len())
        .map(|i| if i % 3 == 0 { 0.0 } else { i as f64 - 4.5 })
        .collect();
    let field = basis.reconstruct(&wanted).unwrap();
    let field_path = dir.path().join("field.npy");
    write_face_vectors(&field_path, &space.to_face_vectors(&field).unwrap()).unwrap();
    let output = tvf()
        .arg("coefficients")
        .arg(&mesh_path)
        .arg(&field_path)
        .arg("--basis")
        .arg(&basis_path)
        .arg("--json")
        .output()
        .unwrap();
    assert_success(&output);
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let entries = json["coefficients"].as_array().unwrap();
    assert_eq!(entries.len(), basis.len());
    for (entry, &w) in entries.iter().zip(&wanted) {
        assert!(
            (entry["coefficient"].as_f64().unwrap() - w).abs() < 1e-10,
            "{entry}"
        );
    }
    assert_eq!(json["gamma"].as_array().unwrap().len(), 2);
    // -k 18: eighteen fields in all, two of them harmonic (genus 1).
    assert_eq!(basis.len(), 18);
    assert_eq!(
        json["alpha"].as_array().unwrap().len() + json["beta"].as_array().unwrap().len(),
        16
    );
    assert!(json["relative_rest_norm"].as_f64().unwrap() < 1e-10);
    assert_eq!(entries[0]["family"], "harmonic");

    // the basis of another mesh is refused
    let other = dir.path().join("torus.obj");
    write_obj(&other, &torus(1.0, 0.4, 12, 8).unwrap()).unwrap();
    let output = tvf()
        .arg("coefficients")
        .arg(&other)
        .arg(&field_path)
        .arg("--basis")
        .arg(&basis_path)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("another mesh"));
}
