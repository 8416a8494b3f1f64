//! Exports parse back with the right counts; writes are atomic and refuse bad data.

use tvf_core::generate::icosphere;
use tvf_core::SurfaceMesh;
use tvf_render::{
    trace_streamlines, write_obj, write_ply, write_vtk, FaceData, RenderError, StreamlineOptions,
};

fn data(faces: usize) -> FaceData {
    FaceData {
        vectors: vec![(
            "field".into(),
            (0..faces).map(|t| [t as f64, 1.0, -0.5]).collect(),
        )],
        scalars: vec![(
            "magnitude".into(),
            (0..faces).map(|t| t as f64 * 0.5).collect(),
        )],
    }
}

#[test]
fn vtk_has_points_polygons_and_cell_vectors() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = SurfaceMesh::from(icosphere(2));
    let path = dir.path().join("field.vtk");
    write_vtk(&path, &mesh, &data(mesh.face_count())).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let find = |prefix: &str| lines.iter().position(|l| l.starts_with(prefix)).unwrap();
    let points = find("POINTS");
    assert_eq!(
        lines[points],
        format!("POINTS {} double", mesh.vertex_count())
    );
    let polygons = find("POLYGONS");
    assert_eq!(polygons, points + 1 + mesh.vertex_count());
    assert_eq!(
        lines[polygons],
        format!("POLYGONS {} {}", mesh.face_count(), 4 * mesh.face_count())
    );
    let first: Vec<usize> = lines[polygons + 1]
        .split(' ')
        .map(|s| s.parse().unwrap())
        .collect();
    assert_eq!(
        first,
        vec![3, mesh.face(0)[0], mesh.face(0)[1], mesh.face(0)[2]]
    );
    let vectors = find("VECTORS field double");
    assert_eq!(
        lines[find("CELL_DATA")],
        format!("CELL_DATA {}", mesh.face_count())
    );
    let v7: Vec<f64> = lines[vectors + 8]
        .split(' ')
        .map(|s| s.parse().unwrap())
        .collect();
    assert_eq!(v7, vec![7.0, 1.0, -0.5]);
    let scalars = find("SCALARS magnitude double 1");
    assert_eq!(lines.len(), scalars + 2 + mesh.face_count());
}

#[test]
fn ply_has_face_properties() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = SurfaceMesh::from(icosphere(1));
    let path = dir.path().join("field.ply");
    write_ply(&path, &mesh, &data(mesh.face_count())).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let (header, body) = text.split_once("end_header\n").unwrap();
    assert!(header.contains(&format!("element vertex {}", mesh.vertex_count())));
    assert!(header.contains(&format!("element face {}", mesh.face_count())));
    assert!(
        header.contains("property double field_x") && header.contains("property double magnitude")
    );
    let rows: Vec<&str> = body.lines().collect();
    assert_eq!(rows.len(), mesh.vertex_count() + mesh.face_count());
    let face5: Vec<f64> = rows[mesh.vertex_count() + 5]
        .split(' ')
        .map(|s| s.parse().unwrap())
        .collect();
    assert_eq!(face5.len(), 1 + 3 + 3 + 1);
    assert_eq!(&face5[4..], &[5.0, 1.0, -0.5, 2.5]);
}

#[test]
fn obj_has_mesh_and_streamline_polylines() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = SurfaceMesh::from(icosphere(3));
    let field: Vec<[f64; 3]> = (0..mesh.face_count()).map(|_| [0.0, 0.0, 1.0]).collect();
    let lines = trace_streamlines(
        mesh.as_triangles().unwrap(),
        &field,
        &StreamlineOptions {
            count: 50,
            ..Default::default()
        },
    )
    .unwrap();
    let polylines: Vec<Vec<[f64; 3]>> = lines.into_iter().map(|l| l.points).collect();
    let path = dir.path().join("lines.obj");
    write_obj(&path, Some(&mesh), &polylines).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let v = text.lines().filter(|l| l.starts_with("v ")).count();
    let f = text.lines().filter(|l| l.starts_with("f ")).count();
    let l: Vec<&str> = text.lines().filter(|l| l.starts_with("l ")).collect();
    let points: usize = polylines
        .iter()
        .filter(|p| p.len() >= 2)
        .map(|p| p.len())
        .sum();
    assert_eq!(v, mesh.vertex_count() + points);
    assert_eq!(f, mesh.face_count());
    assert_eq!(l.len(), polylines.iter().filter(|p| p.len() >= 2).count());
    // Every index refers to an existing vertex.
    for line in l {
        for idx in line.split(' ').skip(1) {
            let i: usize = idx.parse().unwrap();
            assert!(i >= 1 && i <= v);
        }
    }
}

#[test]
fn failed_exports_leave_no_file_behind() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = SurfaceMesh::from(icosphere(1));
    let path = dir.path().join("bad.vtk");
    let bad = FaceData {
        vectors: vec![("has space".into(), vec![[0.0; 3]; mesh.face_count()])],
        scalars: vec![],
    };
    assert!(matches!(
        write_vtk(&path, &mesh, &bad),
        Err(RenderError::InvalidName { .. })
    ));
    let short = FaceData {
        vectors: vec![("field".into(), vec![[0.0; 3]; 3])],
        scalars: vec![],
    };
    assert!(matches!(
        write_ply(&path, &mesh, &short),
        Err(RenderError::FaceCountMismatch { .. })
    ));
    let missing = dir.path().join("no/such/folder/x.obj");
    let err = write_obj(&missing, Some(&mesh), &[]).unwrap_err();
    assert!(err.to_string().contains("x.obj"), "{err}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}
