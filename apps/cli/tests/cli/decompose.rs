//! End-to-end: `tvf decompose` writes three M_X-orthogonal parts that sum to the field, and the
//! potentials.

use crate::common::assert_success;
use std::process::Command;
use tvf_core::discretization::{FieldSampling, HodgeOperators};
use tvf_core::generate::genus_surface;
use tvf_core::io::{load_mesh, write_obj};
use tvf_discretizations::{Conforming, MassLumping};
use tvf_spectral::{read_face_vectors, read_npy, write_face_vectors};

#[test]
fn parts_sum_to_the_field_and_are_orthogonal() {
    let dir = tempfile::tempdir().unwrap();
    let mesh_path = dir.path().join("genus2.obj");
    write_obj(&mesh_path, &genus_surface(2, 4)).unwrap();
    let mesh = load_mesh(&mesh_path)
        .unwrap()
        .mesh
        .into_triangles()
        .unwrap();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let space = complex.face_fields();
    let field: Vec<f64> = (0..space.field_dimension())
        .map(|i| ((i * 7919) % 1000) as f64 / 500.0 - 1.0)
        .collect();
    let vectors = space.to_face_vectors(&field).unwrap();
    let field_path = dir.path().join("field.txt");
    write_face_vectors(&field_path, &vectors).unwrap();
    let out = dir.path().join("parts");
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .arg("decompose")
        .arg(&mesh_path)
        .arg(&field_path)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_success(&output);
    let read = |name: &str| {
        space
            .from_face_vectors(&read_face_vectors(&out.join(format!("{name}.npy"))).unwrap())
            .unwrap()
            .field
    };
    let (a, b, h) = (read("integrable"), read("cointegrable"), read("harmonic"));
    let norm = complex.field_inner(&field, &field);
    for i in 0..field.len() {
        assert!((a[i] + b[i] + h[i] - field[i]).abs() < 1e-10);
    }
    assert!(complex.field_inner(&a, &b).abs() < 1e-10 * norm);
    assert!(complex.field_inner(&a, &h).abs() < 1e-10 * norm);
    assert!(complex.field_inner(&b, &h).abs() < 1e-10 * norm);
    assert!(
        complex.field_inner(&h, &h) > 1e-6 * norm,
        "genus 2 has harmonic fields"
    );
    assert_eq!(
        read_npy(&out.join("potential.npy")).unwrap().shape,
        vec![mesh.vertex_count()]
    );
    assert_eq!(
        read_npy(&out.join("co_potential.npy")).unwrap().shape,
        vec![mesh.edge_count()]
    );
    // the integrable part is the gradient of the potential
    let potential = read_npy(&out.join("potential.npy")).unwrap().data;
    let gradient = complex.gradient_field(&potential);
    for i in 0..field.len() {
        assert!((gradient[i] - a[i]).abs() < 1e-12);
    }

    // a field for another mesh: exit code 1, the file is named
    write_face_vectors(&field_path, &vectors[1..]).unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .arg("decompose")
        .arg(&mesh_path)
        .arg(&field_path)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("field.txt"));
}
