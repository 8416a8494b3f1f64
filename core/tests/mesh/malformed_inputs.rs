//! Every file in `core/tests/data/malformed/` is rejected with its own specific error, the message
//! names the file, and nothing panics.

use std::path::{Path, PathBuf};
use tvf_core::io::{load_mesh, LoadError, LoadErrorKind as K};
use tvf_core::MeshError as M;

/// A predicate on the error, and the 1-based line it must point at (if any).
type Expectation = (&'static str, fn(&K) -> bool, Option<usize>);

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/malformed")
}

const EXPECTED: &[Expectation] = &[
    ("empty.obj", |k| *k == K::Empty, None),
    ("empty.off", |k| *k == K::Empty, None),
    ("empty.ply", |k| *k == K::Empty, None),
    ("comments_only.obj", |k| *k == K::Empty, None),
    ("binary_garbage.obj", |k| *k == K::NotText, Some(1)),
    ("binary_garbage.off", |k| *k == K::NotText, Some(3)),
    (
        "binary_garbage.ply",
        |k| matches!(k, K::Parse { .. }),
        Some(1),
    ),
    (
        "truncated_vertex.obj",
        |k| matches!(k, K::Parse { .. }),
        Some(3),
    ),
    (
        "truncated_faces.off",
        |k| matches!(k, K::Truncated { .. }),
        Some(8),
    ),
    (
        "truncated_vertices.off",
        |k| matches!(k, K::Truncated { .. }),
        Some(7),
    ),
    (
        "truncated_binary.ply",
        |k| matches!(k, K::Truncated { .. }),
        None,
    ),
    (
        "truncated_header.ply",
        |k| matches!(k, K::Truncated { .. }),
        Some(5),
    ),
    (
        "bad_header_type.ply",
        |k| matches!(k, K::Parse { .. }),
        Some(4),
    ),
    (
        "bad_header_format.ply",
        |k| matches!(k, K::Parse { .. }),
        Some(2),
    ),
    (
        // A big-endian header over little-endian data: the indices read as huge numbers.
        "byte_order_mismatch.ply",
        |k| {
            matches!(
                k,
                K::IndexOutOfRange {
                    index: 33554432,
                    vertex_count: 4
                }
            )
        },
        None,
    ),
    (
        "wrong_counts_trailing.off",
        |k| matches!(k, K::TrailingData { .. }),
        Some(7),
    ),
    ("bad_counts.off", |k| matches!(k, K::Parse { .. }), Some(2)),
    (
        "not_off_header.off",
        |k| matches!(k, K::Parse { .. }),
        Some(1),
    ),
    (
        "huge_counts.off",
        |k| matches!(k, K::Truncated { .. }),
        Some(4),
    ),
    (
        "huge_counts.ply",
        |k| matches!(k, K::Truncated { .. }),
        None,
    ),
    ("huge_list.ply", |k| matches!(k, K::Truncated { .. }), None),
    (
        "zero_index.obj",
        |k| matches!(k, K::IndexOutOfRange { index: 0, .. }),
        Some(4),
    ),
    (
        "negative_index_out_of_range.obj",
        |k| {
            matches!(
                k,
                K::IndexOutOfRange {
                    index: -4,
                    vertex_count: 3
                }
            )
        },
        Some(4),
    ),
    (
        "index_out_of_range.obj",
        |k| {
            matches!(
                k,
                K::IndexOutOfRange {
                    index: 9,
                    vertex_count: 3
                }
            )
        },
        Some(4),
    ),
    (
        "index_out_of_range.off",
        |k| {
            matches!(
                k,
                K::IndexOutOfRange {
                    index: 3,
                    vertex_count: 3
                }
            )
        },
        Some(6),
    ),
    (
        "negative_index.off",
        |k| matches!(k, K::IndexOutOfRange { index: -1, .. }),
        Some(6),
    ),
    (
        "index_out_of_range.ply",
        |k| {
            matches!(
                k,
                K::IndexOutOfRange {
                    index: 5,
                    vertex_count: 3
                }
            )
        },
        Some(13),
    ),
    (
        "nan_coordinate.obj",
        |k| matches!(k, K::NonFiniteCoordinate { vertex: 1 }),
        Some(2),
    ),
    (
        "inf_coordinate.off",
        |k| matches!(k, K::NonFiniteCoordinate { vertex: 2 }),
        Some(5),
    ),
    (
        "nan_coordinate.ply",
        |k| matches!(k, K::NonFiniteCoordinate { vertex: 2 }),
        None,
    ),
    (
        "non_manifold_edge.obj",
        |k| {
            matches!(
                k,
                K::Mesh(M::NonManifoldEdge {
                    a: 0,
                    b: 1,
                    face_count: 3
                })
            )
        },
        None,
    ),
    (
        "bowtie.obj",
        |k| matches!(k, K::Mesh(M::NonManifoldVertex { vertex: 0, fans: 2 })),
        Some(2),
    ),
    (
        "double_cone.off",
        |k| matches!(k, K::Mesh(M::NonManifoldVertex { vertex: 0, fans: 2 })),
        Some(3),
    ),
    (
        "moebius.obj",
        |k| matches!(k, K::Mesh(M::NonOrientable { .. })),
        Some(38),
    ),
    (
        "mixed_orientation.obj",
        |k| matches!(k, K::Mesh(M::InconsistentOrientation { face_b: 5, .. })),
        Some(12),
    ),
    (
        "repeated_index.obj",
        |k| matches!(k, K::Mesh(M::RepeatedVertexInFace { face: 1, vertex: 1 })),
        Some(6),
    ),
    (
        "zero_area.obj",
        |k| matches!(k, K::Mesh(M::ZeroAreaFace { face: 2 })),
        Some(7),
    ),
    (
        "coincident_corners.off",
        |k| matches!(k, K::Mesh(M::ZeroAreaFace { face: 1 })),
        Some(8),
    ),
    ("no_faces.obj", |k| *k == K::Mesh(M::NoFaces), None),
    ("point_cloud.ply", |k| *k == K::Mesh(M::NoFaces), None),
    (
        "face_too_small.obj",
        |k| *k == K::FaceTooSmall { corners: 2 },
        Some(4),
    ),
    (
        "face_too_small.off",
        |k| *k == K::FaceTooSmall { corners: 2 },
        Some(6),
    ),
    ("bad_number.obj", |k| matches!(k, K::Parse { .. }), Some(2)),
    (
        "bad_face_token.obj",
        |k| matches!(k, K::Parse { .. }),
        Some(4),
    ),
    ("zero_weight.obj", |k| matches!(k, K::Parse { .. }), Some(1)),
    (
        "mesh.stl",
        |k| matches!(k, K::UnknownFormat { extension } if extension == "stl"),
        None,
    ),
    (
        "missing_vertex_indices.ply",
        |k| matches!(k, K::Parse { .. }),
        Some(9),
    ),
    (
        "trailing_data.ply",
        |k| matches!(k, K::TrailingData { .. }),
        Some(14),
    ),
];

fn load_without_panic(path: &Path) -> Result<(), LoadError> {
    std::panic::catch_unwind(|| load_mesh(path).map(|_| ()))
        .unwrap_or_else(|_| panic!("{}: the reader panicked", path.display()))
}

#[test]
fn every_malformed_file_gives_its_specific_error() {
    let mut failures = Vec::new();
    for &(name, expected, line) in EXPECTED {
        let path = corpus().join(name);
        match load_without_panic(&path) {
            Ok(()) => failures.push(format!("{name}: loaded without error")),
            Err(error) => {
                let message = error.to_string();
                if !expected(&error.kind) {
                    failures.push(format!("{name}: wrong error {:?}", error.kind));
                }
                if error.line != line {
                    failures.push(format!("{name}: line {:?}, expected {line:?}", error.line));
                }
                if error.path != path || !message.contains(name) {
                    failures.push(format!("{name}: message does not name the file: {message}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_corpus_is_complete_and_covered() {
    let mut files: Vec<String> = std::fs::read_dir(corpus())
        .unwrap()
        .map(|entry| entry.unwrap().file_name().into_string().unwrap())
        .filter(|name| name != "README.md")
        .collect();
    files.sort();
    let mut listed: Vec<String> = EXPECTED.iter().map(|e| e.0.to_string()).collect();
    listed.sort();
    assert_eq!(
        files, listed,
        "every corpus file has exactly one expectation"
    );
    assert!(files.len() >= 25);
}

#[test]
fn errors_of_different_kinds_are_distinguished() {
    // Non-orientable and merely inconsistently oriented must not be confused.
    let moebius = load_mesh(corpus().join("moebius.obj")).unwrap_err();
    let mixed = load_mesh(corpus().join("mixed_orientation.obj")).unwrap_err();
    assert!(moebius.to_string().contains("non-orientable"), "{moebius}");
    assert!(
        mixed.to_string().contains("inconsistently oriented"),
        "{mixed}"
    );
}
