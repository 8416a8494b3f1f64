//! End-to-end: the outputs for numpy — `tvf operators --format npz` (zips in the layout of
//! `scipy.sparse.save_npz`, entries equal to the Matrix Market files), `vertex_map.npy` with
//! unreferenced input vertices and the `vertex_order` of `info.json`, and
//! `tvf basis --export DIR` (the arrays of the basis, the eigenvalues of `tvf spectrum`).

use std::io::Read;
use std::path::Path;
use std::process::Command;

fn tvf(args: &[&str]) -> std::process::Output {
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "tvf {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// The header dict and the data bytes of a `.npy` file.
fn npy(bytes: &[u8]) -> (String, Vec<u8>) {
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
    let length = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    assert_eq!((10 + length) % 64, 0, "header not aligned");
    let header = String::from_utf8(bytes[10..10 + length].to_vec()).unwrap();
    (header, bytes[10 + length..].to_vec())
}

fn int64s(data: &[u8]) -> Vec<i64> {
    data.chunks(8)
        .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

fn float64s(data: &[u8]) -> Vec<f64> {
    data.chunks(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

fn npz_member(path: &Path, name: &str) -> Vec<u8> {
    let mut archive = zip::ZipArchive::new(std::fs::File::open(path).unwrap()).unwrap();
    let mut bytes = Vec::new();
    archive
        .by_name(name)
        .unwrap()
        .read_to_end(&mut bytes)
        .unwrap();
    bytes
}

#[test]
fn npz_matrices_and_the_vertex_map_with_unreferenced_vertices() {
    let dir = tempfile::tempdir().unwrap();
    // An octahedron after two stray vertices (input 0 and 3 are used by no face).
    let mesh = dir.path().join("stray.obj");
    std::fs::write(
        &mesh,
        "v 9 9 9\nv 1 0 0\nv -1 0 0\nv 5 5 5\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
         f 2 5 7\nf 5 3 7\nf 3 6 7\nf 6 2 7\nf 5 2 8\nf 3 5 8\nf 6 3 8\nf 2 6 8\n",
    )
    .unwrap();
    let (npz, mtx) = (dir.path().join("npz"), dir.path().join("mtx"));
    let mesh = mesh.to_str().unwrap();
    tvf(&[
        "operators",
        mesh,
        "--format",
        "npz",
        "-o",
        npz.to_str().unwrap(),
    ]);
    tvf(&["operators", mesh, "-o", mtx.to_str().unwrap()]);

    let (header, data) = npy(&std::fs::read(npz.join("vertex_map.npy")).unwrap());
    assert!(
        header.contains("'descr': '<i8'") && shape_is(&header, "(6,)"),
        "{header}"
    );
    assert_eq!(int64s(&data), vec![1, 2, 4, 5, 6, 7]);
    let info = std::fs::read_to_string(mtx.join("info.json")).unwrap();
    assert!(
        info.contains("without the 2 unreferenced ones (6 of 8 kept)"),
        "{info}"
    );
    assert!(!info.contains("\"as in the input mesh\""));

    // d0 of the conforming complex: 2F × V = 16 × 6, in scipy's CSR layout.
    let d0 = npz.join("d0.npz");
    let (header, format) = npy(&npz_member(&d0, "format.npy"));
    assert!(header.contains("'descr': '|S3'") && shape_is(&header, "()"));
    assert_eq!(format, b"csr");
    assert_eq!(int64s(&npy(&npz_member(&d0, "shape.npy")).1), vec![16, 6]);
    let indptr = int64s(&npy(&npz_member(&d0, "indptr.npy")).1);
    let indices = int64s(&npy(&npz_member(&d0, "indices.npy")).1);
    let data = float64s(&npy(&npz_member(&d0, "data.npy")).1);
    assert_eq!(indptr.len(), 17);
    assert_eq!(*indptr.last().unwrap() as usize, data.len());
    assert_eq!(indices.len(), data.len());
    // The same entries as the Matrix Market file (1-based there).
    let text = std::fs::read_to_string(mtx.join("d0.mtx")).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('%'));
    let size: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(size[..2], [16, 6]);
    for line in lines {
        let parts: Vec<&str> = line.split_whitespace().collect();
        let (i, j): (usize, i64) = (parts[0].parse().unwrap(), parts[1].parse().unwrap());
        let value: f64 = parts[2].parse().unwrap();
        let row = (indptr[i - 1] as usize)..(indptr[i] as usize);
        let k = row
            .clone()
            .find(|&k| indices[k] == j - 1)
            .expect("entry in the npz");
        assert_eq!(data[k], value);
    }
}

#[test]
fn basis_export_writes_the_arrays_of_the_basis() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("basis");
    let file = dir.path().join("b.tvfb");
    tvf(&[
        "basis",
        "--example",
        "torus",
        "-k",
        "6",
        "--export",
        out.to_str().unwrap(),
        "-o",
        file.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(file.exists());
    let spectrum = tvf(&["spectrum", "--example", "torus", "-k", "6", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&spectrum.stdout).unwrap();
    let expected: Vec<f64> = json["eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let (header, data) = npy(&std::fs::read(out.join("eigenvalues.npy")).unwrap());
    assert!(shape_is(&header, "(6,)"), "{header}");
    let eigenvalues = float64s(&data);
    for (a, b) in eigenvalues.iter().zip(&expected) {
        assert!(
            (a - b).abs() <= 1e-9 * expected[5],
            "{eigenvalues:?} vs {expected:?}"
        );
    }
    let (header, data) = npy(&std::fs::read(out.join("families.npy")).unwrap());
    assert!(header.contains("'descr': '<U12'"), "{header}");
    let first: String = data[..4 * 12]
        .chunks(4)
        .map(|c| char::from_u32(u32::from_le_bytes(c.try_into().unwrap())).unwrap())
        .filter(|&c| c != '\0')
        .collect();
    assert_eq!(first, "harmonic");
    let faces = 2304;
    for (name, shape) in [
        ("fields.npy", format!("({faces}, 3, 6)")),
        ("frames.npy", format!("({faces}, 2, 3)")),
        ("coefficients.npy", format!("({}, 6)", 2 * faces)),
    ] {
        let (header, data) = npy(&std::fs::read(out.join(name)).unwrap());
        assert!(shape_is(&header, &shape), "{name}: {header}");
        let values = float64s(&data);
        assert!(values.iter().all(|x| x.is_finite()));
        if name == "frames.npy" {
            // Orthonormal frames.
            let (e1, e2) = (&values[0..3], &values[3..6]);
            let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
            assert!((dot(e1, e1) - 1.0).abs() < 1e-12 && dot(e1, e2).abs() < 1e-12);
        }
    }
}

/// Whether the `.npy` header's shape is `shape`, compared as tuples of numbers (numpy writes
/// `(6,)` and `(4, 3)`, npyz `(6, )` and `(4, 3, )`: the same tuples).
fn shape_is(header: &str, shape: &str) -> bool {
    let numbers = |tuple: &str| -> Vec<String> {
        tuple
            .trim_matches(|c| c == '(' || c == ')')
            .split(',')
            .map(|n| n.trim().to_string())
            .filter(|n| !n.is_empty())
            .collect()
    };
    let Some(start) = header.find("'shape': (") else {
        return false;
    };
    let rest = &header[start + "'shape': ".len()..];
    let Some(end) = rest.find(')') else {
        return false;
    };
    numbers(&rest[..=end]) == numbers(shape)
}
