//! Polygon meshes from files: kept as polygons, written back as polygons, the errors of a bad
//! polygon naming the file and the line, non-convex polygons accepted with a warning and drawn
//! without a folded triangle.

use tvf_core::generate::{cube_sphere, dual, icosphere, quad_torus};
use tvf_core::geometry::{cross, dot, norm, sub};
use tvf_core::io::{load_mesh, parse_mesh_bytes, save_mesh, LoadErrorKind, MeshFormat};
use tvf_core::{MeshError, SurfaceMesh, ValidationWarning};

/// A file's text, the line its error must name (0: not checked) and the error it must be.
type BadPolygonCase = (String, usize, fn(&MeshError) -> bool);

fn parse(text: &str) -> Result<tvf_core::io::LoadedMesh, tvf_core::io::LoadError> {
    parse_mesh_bytes(text.as_bytes(), MeshFormat::Obj, "poly.obj")
}

#[test]
fn polygon_meshes_round_trip_through_obj_and_ply_as_polygons() {
    let dir = tempfile::tempdir().unwrap();
    let meshes = [
        ("quad-torus", quad_torus(1.0, 0.4, 12, 6).unwrap()),
        ("cube-sphere", cube_sphere(3).unwrap()),
        ("dual", dual(&icosphere(1)).unwrap()),
    ];
    for (name, mesh) in meshes {
        for extension in ["obj", "ply"] {
            let path = dir.path().join(format!("{name}.{extension}"));
            save_mesh(&path, &mesh).unwrap();
            let loaded = load_mesh(&path).unwrap();
            let SurfaceMesh::Polygons(read) = &loaded.mesh else {
                panic!("{name}.{extension} was read as triangles");
            };
            assert_eq!(read.positions(), mesh.positions(), "{name}.{extension}");
            assert_eq!(read.faces(), mesh.faces(), "{name}.{extension}");
            assert_eq!(loaded.mesh.fingerprint(), mesh.fingerprint());
            assert!(loaded.report.warnings.is_empty(), "{:?}", loaded.report);
        }
    }
}

#[test]
fn a_bad_polygon_is_an_error_naming_the_file_the_line_and_the_problem() {
    let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nv 0.5 0.5 1\n";
    let pentagram: String = (0..5)
        .map(|k| {
            let angle = (72.0 * k as f64).to_radians();
            format!("v {} {} 0\n", angle.cos(), angle.sin())
        })
        .collect();
    let cases: Vec<BadPolygonCase> = vec![
        (format!("{square}f 1 2 2 3\n"), 8, |e| {
            matches!(e, MeshError::RepeatedVertexInFace { face: 0, .. })
        }),
        (
            "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3 4\n".to_string(),
            5,
            |e| matches!(e, MeshError::ZeroAreaFace { face: 0 }),
        ),
        (format!("{pentagram}f 1 3 5 2 4\n"), 6, |e| {
            matches!(e, MeshError::PolygonFolds { face: 0, .. })
        }),
        // Two quads sharing the side 2–3 in the same direction.
        (format!("{square}f 1 2 3 4\nf 2 3 6 5\n"), 9, |e| {
            matches!(e, MeshError::InconsistentOrientation { .. })
        }),
        // Three polygons on the side 1–2.
        (format!("{square}f 1 2 3 4\nf 2 1 7\nf 1 2 6 5\n"), 0, |e| {
            matches!(e, MeshError::NonManifoldEdge { .. })
        }),
    ];
    for (text, line, expected) in cases {
        let error = parse(&text).unwrap_err();
        let message = error.to_string();
        assert!(message.contains("poly.obj"), "{message}");
        if line > 0 {
            assert_eq!(error.line, Some(line), "{message}");
        }
        match &error.kind {
            LoadErrorKind::Mesh(mesh_error) => assert!(expected(mesh_error), "{message}"),
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn a_concave_polygon_is_kept_with_a_warning_and_drawn_without_folds() {
    let loaded =
        parse("v 0 0 0\nv 4 0 0\nv 4 4 0\nv 2 1 0\nv 0 4 0\n# notch\nf 1 2 3 4 5\n").unwrap();
    assert_eq!(
        loaded.report.warnings,
        vec![ValidationWarning::NonConvexPolygons {
            count: 1,
            first_face: 0,
            first_line: Some(7),
        }]
    );
    let mesh = &loaded.mesh;
    // The square of side 4 less the notch (4,4)-(2,1)-(0,4) of area 6.
    assert!((mesh.face_area(0) - 10.0).abs() < 1e-12);
    let display = mesh.display();
    let mut drawn_area = 0.0;
    for t in 0..display.face_count() {
        let [a, b, c] = display.faces()[t].map(|v| display.positions()[v]);
        let normal = cross(sub(b, a), sub(c, a));
        assert!(
            dot(normal, [0.0, 0.0, 1.0]) > 0.0,
            "display triangle {t} folds"
        );
        drawn_area += norm(normal) / 2.0;
    }
    assert!((drawn_area - 10.0).abs() < 1e-12, "{drawn_area}");
}
