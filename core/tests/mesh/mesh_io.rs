//! Readers and writers: round trips, the three formats agree, errors name file and line.

use std::path::Path;
use tvf_core::generate::{genus_surface, icosphere};
use tvf_core::io::{
    load_mesh, parse_mesh_bytes, save_mesh, write_obj, write_ply, LoadErrorKind, MeshFormat,
};
use tvf_core::{FaceList, MeshError, ValidationWarning};

const SQUARE_OFF: &str = "OFF\n# a unit square\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n\
                          3 0 1 2\n3 0 2 3\n";

#[test]
fn obj_and_ply_round_trips_are_exact() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = genus_surface(2, 6);
    for name in ["out.obj", "out.ply", "OUT.PLY"] {
        let path = dir.path().join(name);
        save_mesh(&path, &mesh).unwrap();
        let loaded = load_mesh(&path).unwrap();
        assert_eq!(loaded.mesh.positions(), mesh.positions(), "{name}");
        assert_eq!(
            loaded.mesh.to_face_list(),
            FaceList::from_triangles(mesh.faces()),
            "{name}"
        );
        assert!(loaded.report.warnings.is_empty());
    }
    // Only the final files exist: no temporary files are left behind.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 3);
}

#[test]
fn overwriting_replaces_the_whole_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mesh.obj");
    write_obj(&path, &icosphere(3)).unwrap();
    write_obj(&path, &icosphere(0)).unwrap();
    assert_eq!(load_mesh(&path).unwrap().mesh.face_count(), 20);
    let ply = dir.path().join("mesh.ply");
    write_ply(&ply, &icosphere(2)).unwrap();
    write_ply(&ply, &icosphere(1)).unwrap();
    assert_eq!(load_mesh(&ply).unwrap().mesh.face_count(), 80);
}

#[test]
fn writing_to_a_missing_directory_or_unknown_extension_fails_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no/such/dir/mesh.obj");
    let error = save_mesh(&missing, &icosphere(0)).unwrap_err().to_string();
    assert!(error.contains("mesh.obj"), "{error}");
    let error = save_mesh(dir.path().join("mesh.stl"), &icosphere(0)).unwrap_err();
    assert!(error.to_string().contains("mesh.stl"));
}

#[test]
fn off_ascii_ply_binary_ply_and_obj_agree() {
    let off = parse_mesh_bytes(SQUARE_OFF.as_bytes(), MeshFormat::Off, "square.off").unwrap();
    let ascii_ply = "ply\nformat ascii 1.0\ncomment square\nelement vertex 4\n\
                     property float x\nproperty float y\nproperty float z\nproperty uchar red\n\
                     element face 1\nproperty list uchar int vertex_indices\nend_header\n\
                     0 0 0 255\n1 0 0 255\n1 1 0 255\n0 1 0 255\n4 0 1 2 3\n";
    let ply = parse_mesh_bytes(ascii_ply.as_bytes(), MeshFormat::Ply, "square.ply").unwrap();
    let obj = parse_mesh_bytes(
        b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
        MeshFormat::Obj,
        "square.obj",
    )
    .unwrap();
    let mut binary = b"ply\nformat binary_little_endian 1.0\nelement vertex 4\n\
                       property double x\nproperty double y\nproperty double z\n\
                       element edge 1\nproperty list uchar ushort vertex_pair\n\
                       element face 1\nproperty list int uint vertex_indices\n\
                       property short flags\nend_header\n"
        .to_vec();
    for p in off.mesh.positions() {
        for x in p {
            binary.extend(x.to_le_bytes());
        }
    }
    binary.extend([2, 0, 0, 1, 0]);
    for face in [[0u32, 1, 2, 3]] {
        binary.extend(4i32.to_le_bytes());
        for v in face {
            binary.extend(v.to_le_bytes());
        }
        binary.extend(7i16.to_le_bytes());
    }
    let binary = parse_mesh_bytes(&binary, MeshFormat::Ply, "square_bin.ply").unwrap();
    // The square is one quad in the OBJ and both PLYs (polygons are kept as polygons), two
    // triangles in the OFF.
    for other in [&ply, &binary] {
        assert_eq!(other.mesh.positions(), obj.mesh.positions());
        assert_eq!(other.mesh.to_face_list(), obj.mesh.to_face_list());
    }
    assert_eq!(obj.mesh.positions(), off.mesh.positions());
    assert_eq!(obj.mesh.face_count(), 1);
    assert!(!obj.mesh.is_triangle_mesh() && off.mesh.is_triangle_mesh());
    assert_eq!(off.mesh.face_count(), 2);
    for loaded in [&off, &obj] {
        assert_eq!(loaded.mesh.boundary_loops().len(), 1);
        assert!((loaded.mesh.total_area() - 1.0).abs() < 1e-15);
    }
    assert!((off.report.max_angle_deg - 90.0).abs() < 1e-12);
    assert!((obj.report.max_angle_deg - 90.0).abs() < 1e-12);
}

#[test]
fn unreferenced_and_duplicate_vertices_are_reported() {
    let text = b"v 9 9 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0\nv 1 0 0\nv 0 -1 0\n\
                 f 2 3 4\nf 5 7 6\n";
    let loaded = parse_mesh_bytes(text, MeshFormat::Obj, "seam.obj").unwrap();
    assert_eq!(loaded.mesh.vertex_count(), 6);
    assert_eq!(loaded.mesh.component_count(), 2);
    assert_eq!(loaded.report.unreferenced_vertices(), 1);
    assert_eq!(loaded.report.duplicate_vertices(), 2);
    assert_eq!(loaded.report.original_vertex, vec![1, 2, 3, 4, 5, 6]);
    assert_eq!(
        loaded.report.warnings[1],
        ValidationWarning::DuplicateVertices {
            count: 2,
            first: 4,
            duplicate_of: 1
        }
    );
}

#[test]
fn inward_closed_mesh_gets_a_warning() {
    let mesh = icosphere(1);
    let flipped: String = mesh
        .positions()
        .iter()
        .map(|p| format!("v {} {} {}\n", p[0], p[1], p[2]))
        .chain(
            mesh.faces()
                .iter()
                .map(|f| format!("f {} {} {}\n", f[0] + 1, f[2] + 1, f[1] + 1)),
        )
        .collect();
    let loaded = parse_mesh_bytes(flipped.as_bytes(), MeshFormat::Obj, "inward.obj").unwrap();
    assert!(matches!(
        loaded.report.warnings.as_slice(),
        [ValidationWarning::InwardNormals { components: 1, signed_volume, .. }]
            if *signed_volume < 0.0
    ));
}

/// Two octahedra, the second reversed and smaller: the total signed volume is positive, but the
/// reversed component is found and named.
#[test]
fn one_reversed_component_among_others_is_named() {
    let mut text = String::new();
    let mut faces_written = 0;
    for (k, (scale, reversed)) in [(2.0, false), (1.0, true)].into_iter().enumerate() {
        let offset = 6 * k;
        for p in [
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ] {
            let x = 10.0 * k as f64;
            text += &format!("v {} {} {}\n", x + scale * p[0], scale * p[1], scale * p[2]);
        }
        for [a, b, c] in [
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ] {
            let [b, c] = if reversed { [c, b] } else { [b, c] };
            text += &format!(
                "f {} {} {}\n",
                offset + a + 1,
                offset + b + 1,
                offset + c + 1
            );
            faces_written += 1;
        }
    }
    let loaded = parse_mesh_bytes(text.as_bytes(), MeshFormat::Obj, "two.obj").unwrap();
    assert_eq!(loaded.mesh.face_count(), faces_written);
    assert!(
        loaded.mesh.signed_volume() > 0.0,
        "the total hides the reversed part"
    );
    let warning = loaded
        .report
        .warnings
        .iter()
        .find(|w| matches!(w, ValidationWarning::InwardNormals { .. }))
        .expect("the reversed octahedron is reported");
    assert!(matches!(
        warning,
        ValidationWarning::InwardNormals {
            components: 1,
            first_component: 1,
            first_face: 8,
            ..
        }
    ));
    assert!(warning.to_string().contains("component 1"), "{warning}");
}

/// A UTF-8 byte-order mark before the first line changes nothing, in every format (it used to
/// hide the first OBJ vertex, shifting every index by one).
#[test]
fn a_leading_byte_order_mark_is_skipped_in_every_format() {
    const BOM: &str = "\u{feff}";
    let obj = "v 9 9 9\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 2 3 4\nf 2 4 5\n";
    let ascii_ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n\
                     property float y\nproperty float z\nelement face 2\n\
                     property list uchar int vertex_indices\nend_header\n\
                     0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    let mut binary_ply = b"ply\nformat binary_little_endian 1.0\nelement vertex 4\n\
                           property double x\nproperty double y\nproperty double z\n\
                           element face 2\nproperty list uchar int vertex_indices\nend_header\n"
        .to_vec();
    for p in [
        [0.0f64, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ] {
        binary_ply.extend(p.iter().flat_map(|x| x.to_le_bytes()));
    }
    for face in [[0i32, 1, 2], [0, 2, 3]] {
        binary_ply.push(3);
        binary_ply.extend(face.iter().flat_map(|v| v.to_le_bytes()));
    }
    for (bytes, format) in [
        (obj.as_bytes().to_vec(), MeshFormat::Obj),
        (SQUARE_OFF.as_bytes().to_vec(), MeshFormat::Off),
        (ascii_ply.as_bytes().to_vec(), MeshFormat::Ply),
        (binary_ply, MeshFormat::Ply),
    ] {
        let plain = parse_mesh_bytes(&bytes, format, "plain").unwrap();
        let with_bom = [BOM.as_bytes(), &bytes].concat();
        let marked = parse_mesh_bytes(&with_bom, format, "marked")
            .unwrap_or_else(|e| panic!("{format:?}: {e}"));
        assert_eq!(
            marked.mesh.positions(),
            plain.mesh.positions(),
            "{format:?}"
        );
        assert_eq!(
            marked.mesh.to_face_list(),
            plain.mesh.to_face_list(),
            "{format:?}"
        );
        assert_eq!(marked.report.warnings, plain.report.warnings, "{format:?}");
        assert!((marked.mesh.total_area() - 1.0).abs() < 1e-12, "{format:?}");
    }
}

#[test]
fn errors_name_the_file_and_line() {
    let text = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n# comment\nf 1 2 3\nf 1 2 7\n";
    let error = parse_mesh_bytes(text, MeshFormat::Obj, Path::new("dir/bad.obj")).unwrap_err();
    assert_eq!(error.line, Some(6));
    assert_eq!(
        error.kind,
        LoadErrorKind::IndexOutOfRange {
            index: 7,
            vertex_count: 3
        }
    );
    assert_eq!(
        error.to_string(),
        "dir/bad.obj:6: vertex index 7 is out of range: the file has 3 vertices"
    );
    // A validation error is located at the offending face's line.
    let text = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 4 3\n";
    let error = parse_mesh_bytes(text, MeshFormat::Obj, "flip.obj").unwrap_err();
    assert_eq!(error.line, Some(6));
    assert!(matches!(
        error.kind,
        LoadErrorKind::Mesh(MeshError::InconsistentOrientation { .. })
    ));
}

#[test]
fn missing_file_and_unknown_extension() {
    let error = load_mesh("/nonexistent/dir/mesh.obj").unwrap_err();
    assert!(matches!(error.kind, LoadErrorKind::Unreadable { .. }));
    assert!(error.to_string().starts_with("/nonexistent/dir/mesh.obj: "));
    let error = load_mesh("mesh.stl").unwrap_err();
    assert_eq!(
        error.kind,
        LoadErrorKind::UnknownFormat {
            extension: "stl".into()
        }
    );
}

#[test]
fn huge_counts_of_empty_elements_do_not_hang() {
    // Found by cargo fuzz: an element without properties and a count near 2^64 used to be
    // iterated instance by instance. It stores no data, so the file is a valid triangle.
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                property float z\nelement padding 18000000000000000000\nelement face 1\n\
                property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let loaded = parse_mesh_bytes(text.as_bytes(), MeshFormat::Ply, "padding.ply").unwrap();
    assert_eq!(loaded.mesh.face_count(), 1);
}

#[test]
fn big_endian_binary_ply_reads_like_little_endian() {
    // A tetrahedron with float coordinates, a ushort property between them, uchar/int lists.
    let positions: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let faces: [[i32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
    let file = |format: &str, big: bool| {
        let mut bytes = format!(
            "ply\nformat {format} 1.0\nelement vertex 4\nproperty float x\nproperty ushort tag\n\
             property float y\nproperty float z\nelement face 4\n\
             property list uchar int vertex_indices\nend_header\n"
        )
        .into_bytes();
        for (i, p) in positions.iter().enumerate() {
            let tag = 300 + i as u16;
            let (x, tag, y, z) = if big {
                (
                    p[0].to_be_bytes(),
                    tag.to_be_bytes(),
                    p[1].to_be_bytes(),
                    p[2].to_be_bytes(),
                )
            } else {
                (
                    p[0].to_le_bytes(),
                    tag.to_le_bytes(),
                    p[1].to_le_bytes(),
                    p[2].to_le_bytes(),
                )
            };
            bytes.extend(x);
            bytes.extend(tag);
            bytes.extend(y);
            bytes.extend(z);
        }
        for face in faces {
            bytes.push(3);
            for v in face {
                bytes.extend(if big {
                    v.to_be_bytes()
                } else {
                    v.to_le_bytes()
                });
            }
        }
        bytes
    };
    let big =
        parse_mesh_bytes(&file("binary_big_endian", true), MeshFormat::Ply, "be.ply").unwrap();
    let little = parse_mesh_bytes(
        &file("binary_little_endian", false),
        MeshFormat::Ply,
        "le.ply",
    )
    .unwrap();
    assert_eq!(big.mesh.positions(), little.mesh.positions());
    assert_eq!(big.mesh.to_face_list(), little.mesh.to_face_list());
    assert_eq!(big.mesh.positions()[3], [0.0, 0.0, 1.0]);
    assert!(big.mesh.is_closed());
    // The same bytes declared little-endian are refused (indices out of range).
    let wrong = file("binary_little_endian", true);
    assert!(parse_mesh_bytes(&wrong, MeshFormat::Ply, "wrong.ply").is_err());
}

/// Odd encodings of text meshes: bytes of another encoding in comments are allowed, line ends
/// of a carriage return only are lines, a UTF-16 file and a stray byte-order mark before a
/// keyword are clear errors (the mark used to hide its vertex line), control characters in
/// messages are escaped, and a PLY version other than 1.0 is refused.
#[test]
fn odd_encodings_are_read_or_refused_clearly() {
    let obj = "v 9 9 9\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 2 3 4\nf 2 4 5\n";
    let plain = parse_mesh_bytes(obj.as_bytes(), MeshFormat::Obj, "plain.obj").unwrap();
    let latin1 = [
        b"# cr\xe9\xe9 par un vieil outil\n".as_slice(),
        obj.as_bytes(),
    ]
    .concat();
    let cr_only = obj.replace('\n', "\r");
    for (bytes, what) in [
        (latin1, "Latin-1 comment"),
        (cr_only.into_bytes(), "CR line ends"),
    ] {
        let read = parse_mesh_bytes(&bytes, MeshFormat::Obj, "odd.obj")
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(read.mesh.positions(), plain.mesh.positions(), "{what}");
        assert_eq!(
            read.mesh.to_face_list(),
            plain.mesh.to_face_list(),
            "{what}"
        );
    }
    let utf16: Vec<u8> = [0xFF, 0xFE]
        .into_iter()
        .chain(obj.encode_utf16().flat_map(|u| u.to_le_bytes()))
        .collect();
    let error = parse_mesh_bytes(&utf16, MeshFormat::Obj, "wide.obj").unwrap_err();
    assert!(matches!(error.kind, LoadErrorKind::Utf16), "{error}");
    let twice = format!("\u{feff}\u{feff}{obj}");
    let error = parse_mesh_bytes(twice.as_bytes(), MeshFormat::Obj, "twice.obj").unwrap_err();
    assert_eq!(error.line, Some(1), "{error}");
    assert!(
        error
            .to_string()
            .contains("\\u{feff}v' is not an OBJ keyword"),
        "{error}"
    );
    let nul = obj.replace("v 1 0 0", "v 1\u{0}0 0");
    let error = parse_mesh_bytes(nul.as_bytes(), MeshFormat::Obj, "nul.obj").unwrap_err();
    assert!(error.to_string().contains("1\\u{0}0"), "{error}");
    assert!(!error.to_string().contains('\0'));
    let ply = "ply\nformat ascii 2.0\nelement vertex 3\nproperty float x\nproperty float y\n\
               property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
               end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let error = parse_mesh_bytes(ply.as_bytes(), MeshFormat::Ply, "two.ply").unwrap_err();
    assert!(error.to_string().contains("version '2.0'"), "{error}");
}
