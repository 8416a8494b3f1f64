//! Field files: `.npy` and text round trips, NumPy compatibility, and every rejection.

use std::path::Path;
use tvf_core::discretization::FieldSampling;
use tvf_core::generate::icosphere;
use tvf_discretizations::FaceFields;
use tvf_spectral::{
    read_face_vector_sequence, read_face_vectors, read_npy, read_tangent_field,
    write_face_vector_sequence, write_face_vectors, write_face_vectors_as, write_npy,
    write_tangent_field, FieldFileFormat, FieldIoError, NpyArray, NpyDtype, NpyError,
};

fn sample_vectors(n: usize) -> Vec<[f64; 3]> {
    (0..n)
        .map(|i| {
            let x = i as f64;
            [(0.3 * x).sin() / 3.0, (1.7 * x).cos() * 1e-7, x * 1e5 + 0.1]
        })
        .collect()
}

#[test]
fn npy_and_text_round_trips_are_exact() {
    let dir = tempfile::tempdir().unwrap();
    let vectors = sample_vectors(57);
    for name in ["f.npy", "f.txt", "f.NPY"] {
        let path = dir.path().join(name);
        write_face_vectors(&path, &vectors).unwrap();
        assert_eq!(read_face_vectors(&path).unwrap(), vectors, "{name}");
    }
    let path = dir.path().join("single.npy");
    write_face_vectors_as(&path, &vectors, FieldFileFormat::Npy(NpyDtype::F32)).unwrap();
    let back = read_face_vectors(&path).unwrap();
    for (a, b) in back.iter().zip(&vectors) {
        for c in 0..3 {
            assert_eq!(a[c], (b[c] as f32) as f64);
        }
    }
    assert_eq!(read_npy(&path).unwrap().dtype, NpyDtype::F32);
}

#[test]
fn reads_files_written_by_numpy() {
    // np.save of np.array([[1.5, -2, 3], [0.25, 5, 6e-3]], dtype='<f4') (numpy 2.4).
    let mut bytes =
        b"\x93NUMPY\x01\x00v\x00{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }"
            .to_vec();
    bytes.resize(127, b' ');
    bytes.push(b'\n');
    for x in [1.5f32, -2.0, 3.0, 0.25, 5.0, 6e-3] {
        bytes.extend_from_slice(&x.to_le_bytes());
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("numpy.npy");
    std::fs::write(&path, &bytes).unwrap();
    let v = read_face_vectors(&path).unwrap();
    assert_eq!(v[0], [1.5, -2.0, 3.0]);
    assert_eq!(v[1][2], 6e-3f32 as f64);
    // and our own file has numpy's layout: the same prefix (version 1.0, header length), the
    // data at the same offset and byte for byte the same; the header differs only in the shape
    // tuple's trailing comma, `(2, 3, )`, which numpy reads as `(2, 3)`.
    let ours = NpyArray {
        shape: vec![2, 3],
        data: vec![1.5, -2.0, 3.0, 0.25, 5.0, 6e-3],
        dtype: NpyDtype::F32,
    }
    .to_bytes();
    assert_eq!(ours.len(), bytes.len());
    assert_eq!(ours[..10], bytes[..10]);
    assert_eq!(ours[128..], bytes[128..]);
    let header = std::str::from_utf8(&ours[10..128]).unwrap();
    assert!(header.starts_with("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3"));
}

#[test]
fn fortran_order_big_endian_and_integer_files_are_read() {
    // np.save of np.asfortranarray(np.array([[1, 2, 3], [4, 5, 6]], dtype='>f8')): the columns
    // one after the other, big-endian.
    let file = |descr: &str, fortran: &str, data: &[u8]| {
        let mut bytes = b"\x93NUMPY\x01\x00v\x00".to_vec();
        bytes.extend_from_slice(
            format!("{{'descr': '{descr}', 'fortran_order': {fortran}, 'shape': (2, 3), }}")
                .as_bytes(),
        );
        bytes.resize(127, b' ');
        bytes.push(b'\n');
        bytes.extend_from_slice(data);
        bytes
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fortran.npy");
    let columns: Vec<u8> = [1.0f64, 4.0, 2.0, 5.0, 3.0, 6.0]
        .iter()
        .flat_map(|x| x.to_be_bytes())
        .collect();
    std::fs::write(&path, file(">f8", "True", &columns)).unwrap();
    assert_eq!(
        read_face_vectors(&path).unwrap(),
        vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]
    );
    let path = dir.path().join("int.npy");
    let ints: Vec<u8> = [1i64, -2, 3, 4, 5, 1 << 40]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    std::fs::write(&path, file("<i8", "False", &ints)).unwrap();
    assert_eq!(
        read_face_vectors(&path).unwrap(),
        vec![[1.0, -2.0, 3.0], [4.0, 5.0, (1i64 << 40) as f64]]
    );
}

fn expect_error(path: &Path, check: impl Fn(&FieldIoError) -> bool) {
    let error = read_face_vectors(path).unwrap_err();
    assert!(check(&error), "unexpected error {error:?}");
    let message = error.to_string();
    assert!(
        message.contains(&path.display().to_string()),
        "message does not name the file: {message}"
    );
}

#[test]
fn bad_files_are_rejected_with_the_path() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name);
    expect_error(&p("missing.npy"), |e| matches!(e, FieldIoError::Io { .. }));

    let good = NpyArray {
        shape: vec![2, 3],
        data: vec![1.0; 6],
        dtype: NpyDtype::F64,
    }
    .to_bytes();
    let write = |name: &str, bytes: &[u8]| {
        std::fs::write(p(name), bytes).unwrap();
        p(name)
    };
    let mut complex = good.clone();
    let at = complex.windows(4).position(|w| w == b"<f8'").unwrap();
    complex[at..at + 4].copy_from_slice(b"<c8'");
    expect_error(
        &write("complex.npy", &complex),
        |e| matches!(e, FieldIoError::Npy { source: NpyError::Dtype(d), .. } if d == "<c8"),
    );
    let mut huge = good.clone();
    let at = huge.windows(3).position(|w| w == b"<f8").unwrap();
    huge[at..at + 3].copy_from_slice(b"<u8");
    let data_start = huge.len() - 48;
    huge[data_start..data_start + 8].copy_from_slice(&u64::MAX.to_le_bytes());
    expect_error(&write("huge.npy", &huge), |e| {
        matches!(
            e,
            FieldIoError::Npy {
                source: NpyError::Unrepresentable { index: 0, .. },
                ..
            }
        )
    });
    expect_error(&write("short.npy", &good[..good.len() - 3]), |e| {
        matches!(
            e,
            FieldIoError::Npy {
                source: NpyError::Truncated(_),
                ..
            }
        )
    });
    expect_error(&write("text.npy", b"1 2 3\n"), |e| {
        matches!(
            e,
            FieldIoError::Npy {
                source: NpyError::NotNpy,
                ..
            }
        )
    });
    let wrong_shape = NpyArray {
        shape: vec![3, 2],
        data: vec![1.0; 6],
        dtype: NpyDtype::F64,
    };
    write_npy(&p("shape.npy"), &wrong_shape).unwrap();
    expect_error(
        &p("shape.npy"),
        |e| matches!(e, FieldIoError::Shape { found, .. } if found == &vec![3, 2]),
    );
    let nan = NpyArray {
        shape: vec![2, 3],
        data: vec![1.0, 2.0, 3.0, 4.0, f64::NAN, 6.0],
        dtype: NpyDtype::F64,
    };
    write_npy(&p("nan.npy"), &nan).unwrap();
    expect_error(&p("nan.npy"), |e| {
        matches!(e, FieldIoError::NonFinite { index: 1, .. })
    });
    expect_error(&write("bad.txt", b"1 2 3\n4 five 6\n"), |e| {
        matches!(e, FieldIoError::Text { line: 2, .. })
    });
    let inconsistent = NpyArray {
        shape: vec![2, 3],
        data: vec![1.0; 5],
        dtype: NpyDtype::F64,
    };
    assert!(matches!(
        write_npy(&p("x.npy"), &inconsistent),
        Err(FieldIoError::Inconsistent { .. })
    ));
}

#[test]
fn sequences_round_trip_in_c_order() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("seq.npy");
    let frames: Vec<Vec<[f64; 3]>> = (0..4).map(|_| sample_vectors(11)).collect();
    let frames: Vec<Vec<[f64; 3]>> = frames
        .into_iter()
        .enumerate()
        .map(|(k, f)| {
            f.into_iter()
                .map(|v| [v[0] + k as f64, v[1], v[2]])
                .collect()
        })
        .collect();
    write_face_vector_sequence(&path, &frames, NpyDtype::F64).unwrap();
    let array = read_npy(&path).unwrap();
    assert_eq!(array.shape, vec![11, 3, 4]);
    // element [t][c][k] at (t*3 + c)*T + k
    assert_eq!(array.data[(5 * 3) * 4 + 2], frames[2][5][0]);
    assert_eq!(read_face_vector_sequence(&path).unwrap(), frames);
    assert!(matches!(
        read_face_vector_sequence(&dir.path().join("missing.npy")),
        Err(FieldIoError::Io { .. })
    ));
    write_face_vectors(&dir.path().join("one.npy"), &frames[0]).unwrap();
    assert!(matches!(
        read_face_vector_sequence(&dir.path().join("one.npy")),
        Err(FieldIoError::Shape { .. })
    ));
}

#[test]
fn tangent_fields_are_projected_and_the_normal_part_reported() {
    let mesh = icosphere(1);
    let space = FaceFields::new(&mesh).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let field: Vec<f64> = (0..space.field_dimension())
        .map(|i| (i as f64 * 0.41).sin())
        .collect();
    let path = dir.path().join("tangent.npy");
    write_tangent_field(&path, &space, &field).unwrap();
    let back = read_tangent_field(&path, &space).unwrap();
    for (a, b) in back.field.iter().zip(&field) {
        assert!((a - b).abs() < 1e-14);
    }
    assert!(back.max_normal_part() < 1e-14);
    // add 0.5 n_t to every vector: projected away and reported
    let vectors: Vec<[f64; 3]> = space
        .to_face_vectors(&field)
        .unwrap()
        .iter()
        .enumerate()
        .map(|(t, v)| {
            let n = space.normal(t);
            [v[0] + 0.5 * n[0], v[1] + 0.5 * n[1], v[2] + 0.5 * n[2]]
        })
        .collect();
    let path = dir.path().join("normal.txt");
    write_face_vectors(&path, &vectors).unwrap();
    let back = read_tangent_field(&path, &space).unwrap();
    assert!((back.max_normal_part() - 0.5).abs() < 1e-12);
    for (a, b) in back.field.iter().zip(&field) {
        assert!((a - b).abs() < 1e-12);
    }
    let short = dir.path().join("short.txt");
    write_face_vectors(&short, &vectors[1..]).unwrap();
    let error = read_tangent_field(&short, &space).unwrap_err();
    assert!(matches!(
        error,
        FieldIoError::FaceCount {
            expected: 80,
            found: 79,
            ..
        }
    ));
    assert!(error.to_string().contains("short.txt"));
}
