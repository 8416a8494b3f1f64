//! `--complex DIR` end to end: `tvf operators MESH -o DIR` (Matrix Market and `.npz`), a matrix
//! edited in the written file, and `tvf spectrum` / `tvf analyze` on the folder give the spectrum
//! of the edited matrices — checked against a dense generalized eigensolve of the two scalar
//! pencils here — twice in a row with the default cache, on a closed and an open mesh. Broken
//! folders are refused naming the file; filter, spline and render on an unedited folder give
//! the very results of the catalog entry it was written from. Generated meshes only.

use crate::common::{assert_success, tvf, write_field};
use faer::{Mat, Side};
use sprs::CsMat;
use std::path::{Path, PathBuf};
use tvf_core::generate::{disk, genus_surface, icosphere};
use tvf_core::io::write_obj;
use tvf_core::TriangleMesh;
use tvf_spectral::{read_matrix_market, read_sparse_npz, write_sparse_npz};

/// Runs `tvf args` with the cache in `cache`; returns the output (not checked).
fn run(cache: &Path, args: &[&str]) -> std::process::Output {
    tvf()
        .args(args)
        .arg("--quiet")
        .env("TVF_CACHE_DIR", cache)
        .output()
        .expect("the tvf binary runs")
}

/// Runs `tvf args` and checks it succeeded; returns stdout.
fn succeed(cache: &Path, args: &[&str]) -> String {
    let output = run(cache, args);
    assert_success(&output);
    String::from_utf8(output.stdout).unwrap()
}

/// Runs `tvf args`, checks it failed, and returns stderr.
fn fail(cache: &Path, args: &[&str]) -> String {
    let output = run(cache, args);
    assert!(!output.status.success(), "{args:?} should fail");
    String::from_utf8(output.stderr).unwrap()
}

/// A temporary folder with `mesh` written as `mesh.obj`.
struct Setup {
    dir: tempfile::TempDir,
    mesh: String,
}

impl Setup {
    fn new(mesh: &TriangleMesh) -> Self {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("mesh.obj");
        write_obj(&path, mesh).unwrap();
        Self {
            mesh: path.display().to_string(),
            dir,
        }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn cache(&self) -> PathBuf {
        self.path("cache")
    }

    /// `tvf operators` into `name` in `format`; returns the folder.
    fn operators(&self, name: &str, format: &str) -> String {
        let out = self.path(name).display().to_string();
        succeed(
            &self.cache(),
            &["operators", &self.mesh, "--format", format, "-o", &out],
        );
        out
    }
}

/// Reads the matrix `name` of `folder` in `format` (`mtx` or `npz`).
fn read(folder: &str, name: &str, format: &str) -> CsMat<f64> {
    let path = Path::new(folder).join(format!("{name}.{format}"));
    let file = std::io::BufReader::new(std::fs::File::open(&path).unwrap());
    match format {
        "mtx" => read_matrix_market(file).unwrap(),
        _ => read_sparse_npz(file).unwrap(),
    }
}

/// Edits the entries of matrix `name` in the written file: `.mtx` as text, line by line (the
/// value column), `.npz` through scipy's layout.
fn edit(folder: &str, name: &str, format: &str, change: impl Fn(usize, usize, f64) -> f64) {
    let path = Path::new(folder).join(format!("{name}.{format}"));
    if format == "mtx" {
        let text = std::fs::read_to_string(&path).unwrap();
        let mut lines = text.lines();
        let mut out: Vec<String> = Vec::new();
        // Header and comments, then the size line, untouched.
        for line in lines.by_ref() {
            out.push(line.to_string());
            if !line.starts_with('%') {
                break;
            }
        }
        for line in lines {
            let w: Vec<&str> = line.split_whitespace().collect();
            let (i, j) = (
                w[0].parse::<usize>().unwrap(),
                w[1].parse::<usize>().unwrap(),
            );
            let value = change(i - 1, j - 1, w[2].parse().unwrap());
            out.push(format!("{} {} {value:e}", w[0], w[1]));
        }
        std::fs::write(&path, out.join("\n") + "\n").unwrap();
    } else {
        let matrix = read(folder, name, format);
        let mut changed = matrix.clone();
        let positions: Vec<(usize, usize)> = matrix.iter().map(|(_, ij)| ij).collect();
        for (value, (i, j)) in changed.data_mut().iter_mut().zip(positions) {
            *value = change(i, j, *value);
        }
        let mut bytes = std::io::Cursor::new(Vec::new());
        write_sparse_npz(&mut bytes, &changed).unwrap();
        std::fs::write(&path, bytes.into_inner()).unwrap();
    }
}

/// A change of one stored entry: `(row, col, value) → new value`.
type EntryChange = fn(usize, usize, f64) -> f64;

/// The diagonal of a diagonal matrix.
fn diagonal(a: &CsMat<f64>) -> Vec<f64> {
    assert!(a.iter().all(|(_, (i, j))| i == j), "a diagonal mass");
    (0..a.rows()).map(|i| *a.get(i, i).unwrap()).collect()
}

/// The eigenvalues of `A x = λ diag(b) x` restricted to the nodes `keep`, `A` dense.
fn pencil(a: &Mat<f64>, b: &[f64], keep: &[usize]) -> Vec<f64> {
    let n = keep.len();
    let c = Mat::from_fn(n, n, |r, s| {
        a[(keep[r], keep[s])] / (b[keep[r]] * b[keep[s]]).sqrt()
    });
    c.self_adjoint_eigenvalues(Side::Lower).unwrap()
}

/// The spectrum of the Hodge–Laplacian of the folder's matrices (diagonal masses), harmonic
/// zeros included: the nonzero eigenvalues of the exact pencil `(d0ᵀ M1 d0, M0)` and the
/// co-exact pencil `(d1 M1⁻¹ d1ᵀ, M2⁻¹)` on the free nodes, plus `harmonic` zeros.
fn dense_spectrum(
    folder: &str,
    format: &str,
    fixed_co_potentials: &[usize],
    harmonic: usize,
) -> Vec<f64> {
    let d0 = read(folder, "d0", format).to_csr();
    let d1 = read(folder, "d1", format).to_csr();
    let m0 = diagonal(&read(folder, "M0", format));
    let m1 = diagonal(&read(folder, "M1", format));
    let m2 = diagonal(&read(folder, "M2", format));
    let dense = |a: &CsMat<f64>| {
        let mut m = Mat::<f64>::zeros(a.rows(), a.cols());
        for (&v, (i, j)) in a.iter() {
            m[(i, j)] += v;
        }
        m
    };
    let (d0, d1) = (dense(&d0), dense(&d1));
    let m1_diag = Mat::from_fn(m1.len(), m1.len(), |i, j| if i == j { m1[i] } else { 0.0 });
    let m1_inv = Mat::from_fn(
        m1.len(),
        m1.len(),
        |i, j| if i == j { 1.0 / m1[i] } else { 0.0 },
    );
    let exact = d0.transpose() * &m1_diag * &d0;
    let co_exact = &d1 * &m1_inv * d1.transpose();
    let potentials: Vec<usize> = (0..m0.len()).collect();
    let co_potentials: Vec<usize> = (0..m2.len())
        .filter(|i| !fixed_co_potentials.contains(i))
        .collect();
    let co_mass: Vec<f64> = m2.iter().map(|m| 1.0 / m).collect();
    let mut all = pencil(&exact, &m0, &potentials);
    all.extend(pencil(&co_exact, &co_mass, &co_potentials));
    let largest = all.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let mut nonzero: Vec<f64> = all.into_iter().filter(|x| *x > 1e-9 * largest).collect();
    nonzero.extend(std::iter::repeat_n(0.0, harmonic));
    nonzero.sort_by(f64::total_cmp);
    nonzero
}

/// The eigenvalues `tvf spectrum --json` prints.
fn printed_spectrum(stdout: &str) -> Vec<f64> {
    let json: serde_json::Value = serde_json::from_str(stdout).unwrap();
    json["eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// The eigenvalue column of `tvf analyze`'s coefficients.csv (cached basis).
fn analyzed_eigenvalues(csv: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(csv).unwrap();
    let mut values: Vec<f64> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
        .collect();
    values.sort_by(f64::total_cmp);
    values
}

#[track_caller]
fn assert_close(found: &[f64], expected: &[f64], what: &str) {
    assert_eq!(found.len(), expected.len(), "{what}: counts");
    let scale = expected.iter().fold(1e-300_f64, |m, x| m.max(x.abs()));
    for (k, (a, b)) in found.iter().zip(expected).enumerate() {
        assert!(
            (a - b).abs() <= 1e-8 * scale,
            "{what}: eigenvalue {k} is {a}, the dense pencils give {b}"
        );
    }
}

/// Operators → edit → spectrum (complete, uncached) and analyze (cached basis of 10 fields),
/// twice with different edits, compared with the dense pencils of the edited files.
fn round_trip(mesh: &TriangleMesh, format: &str) {
    let setup = Setup::new(mesh);
    let folder = setup.operators("ops", format);
    let info: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(Path::new(&folder).join("info.json")).unwrap(),
    )
    .unwrap();
    let fixed: Vec<usize> = info["fixed_nodes"]["co_potentials"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap() as usize)
        .collect();
    assert_eq!(
        fixed.is_empty(),
        mesh.is_closed(),
        "fixed co-potentials on the open mesh only"
    );
    let harmonic = info["harmonic_dimension"].as_u64().unwrap() as usize;
    let field = setup.path("field.txt");
    write_field(mesh, &field);
    let all = (2 * mesh.face_count()).to_string();
    let edits: [(&str, EntryChange); 2] = [
        ("M1", |_, _, v| 1.5 * v),
        ("M0", |i, _, v| v * (1.0 + 0.2 * (i as f64).sin())),
    ];
    let mut previous: Option<Vec<f64>> = None;
    for (name, change) in edits {
        edit(&folder, name, format, change);
        let expected = dense_spectrum(&folder, format, &fixed, harmonic);
        let what = format!("{format}, {} faces, {name} edited", mesh.face_count());
        let stdout = succeed(
            &setup.cache(),
            &[
                "spectrum",
                &setup.mesh,
                "--complex",
                &folder,
                "-k",
                &all,
                "--json",
            ],
        );
        assert_close(&printed_spectrum(&stdout), &expected, &what);
        let analysis = setup.path(&format!("analysis-{name}"));
        succeed(
            &setup.cache(),
            &[
                "analyze",
                &setup.mesh,
                field.to_str().unwrap(),
                "--complex",
                &folder,
                "-k",
                "10",
                "-o",
                analysis.to_str().unwrap(),
            ],
        );
        let cached = analyzed_eigenvalues(&analysis.join("coefficients.csv"));
        assert_close(&cached, &expected[..10], &format!("{what} (cached basis)"));
        if let Some(previous) = previous.replace(expected) {
            assert_ne!(
                previous[..10],
                cached[..],
                "the second edit changes the spectrum"
            );
        }
    }
    let cached = std::fs::read_dir(setup.cache()).unwrap().count();
    assert_eq!(cached, 2, "one cached basis per edited folder");
}

#[test]
fn edited_matrix_market_files_give_their_spectrum_on_a_closed_mesh() {
    round_trip(&icosphere(1), "mtx");
}

#[test]
fn edited_npz_files_give_their_spectrum_on_an_open_mesh() {
    round_trip(&disk(3), "npz");
}

#[test]
fn edited_matrix_market_files_give_their_spectrum_on_an_open_mesh() {
    round_trip(&disk(3), "mtx");
}

/// Each broken folder is refused, the error naming the file and the problem.
#[test]
fn broken_folders_are_refused_naming_the_file() {
    let setup = Setup::new(&icosphere(1));
    let cache = setup.cache();
    let attempt = |folder: &str| {
        fail(
            &cache,
            &["spectrum", &setup.mesh, "--complex", folder, "-k", "5"],
        )
    };
    let check = |folder: &str, file: &str, problem: &str| {
        let stderr = attempt(folder);
        let named = Path::new(folder).join(file).display().to_string();
        assert!(
            stderr.contains(&named) && stderr.contains(problem),
            "expected '{named}' and '{problem}' in:\n{stderr}"
        );
    };
    let missing = setup.operators("missing", "mtx");
    std::fs::remove_file(Path::new(&missing).join("M1.mtx")).unwrap();
    check(&missing, "M1.mtx", "missing");

    let shape = setup.operators("shape", "mtx");
    std::fs::write(
        Path::new(&shape).join("M0.mtx"),
        "%%MatrixMarket matrix coordinate real general\n3 3 3\n1 1 1\n2 2 1\n3 3 1\n",
    )
    .unwrap();
    check(
        &shape,
        "M0.mtx",
        "M0 is 3 x 3, but the complex needs 42 x 42",
    );

    type Edit = fn(usize, usize, f64) -> f64;
    let edited: [(&str, &str, &str, Edit, &str, &str); 3] = [
        (
            "nan",
            "M1",
            "npz",
            |i, _, v| if i == 12 { f64::NAN } else { v },
            "M1.npz",
            "row 12 col 12 (0-based): not finite",
        ),
        (
            "not-complex",
            "d0",
            "mtx",
            |i, _, v| if i == 3 { 2.0 * v } else { v },
            "d1.mtx",
            "d1 · d0 is not zero",
        ),
        (
            "negative",
            "M1",
            "mtx",
            |i, _, v| if i == 7 { -v } else { v },
            "M1.mtx",
            "M1 must be positive",
        ),
    ];
    for (case, matrix, format, change, file, problem) in edited {
        let folder = setup.operators(case, format);
        edit(&folder, matrix, format, change);
        check(&folder, file, problem);
    }

    let remapped = setup.operators("remapped", "mtx");
    let mut map: Vec<i64> = (0..42).collect();
    map.swap(4, 5);
    std::fs::write(
        Path::new(&remapped).join("vertex_map.npy"),
        tvf_spectral::npy_bytes(&tvf_spectral::NpyData::I64(&map), &[42]),
    )
    .unwrap();
    check(
        &remapped,
        "vertex_map.npy",
        "mesh vertex 4 is input vertex 5 here",
    );

    // Written for another mesh: the fingerprint of info.json.
    let other = Setup::new(&icosphere(2));
    let stderr = fail(
        &cache,
        &["spectrum", &other.mesh, "--complex", &missing, "-k", "5"],
    );
    assert!(
        stderr.contains("info.json") && stderr.contains("another mesh"),
        "{stderr}"
    );
}

/// A basis file computed with `--complex` reopens with the same folder and is refused with an
/// edited one, naming the matrix that differs.
#[test]
fn basis_files_of_a_folder_are_tied_to_its_matrices() {
    let setup = Setup::new(&icosphere(1));
    let cache = setup.cache();
    let folder = setup.operators("ops", "mtx");
    let field = setup.path("field.txt");
    write_field(&icosphere(1), &field);
    let basis = setup.path("basis.tvfb").display().to_string();
    succeed(
        &cache,
        &[
            "basis",
            &setup.mesh,
            "--complex",
            &folder,
            "-k",
            "12",
            "-o",
            &basis,
        ],
    );
    let filter = |out: &str| {
        run(
            &cache,
            &[
                "filter",
                &setup.mesh,
                field.to_str().unwrap(),
                "--basis",
                &basis,
                "--complex",
                &folder,
                "-o",
                out,
            ],
        )
    };
    assert_success(&filter(setup.path("a.txt").to_str().unwrap()));
    let stderr = fail(
        &cache,
        &[
            "filter",
            &setup.mesh,
            field.to_str().unwrap(),
            "--basis",
            &basis,
            "-o",
            "x.txt",
        ],
    );
    assert!(stderr.contains("--complex DIR"), "{stderr}");
    edit(&folder, "M1", "mtx", |_, _, v| 2.0 * v);
    let refused = filter(setup.path("b.txt").to_str().unwrap());
    let stderr = String::from_utf8(refused.stderr).unwrap();
    assert!(!refused.status.success());
    assert!(
        stderr.contains("other matrices") && stderr.contains("M1 differs"),
        "{stderr}"
    );
}

/// filter, spline and render on an unedited folder: the same output as the catalog entry the
/// folder was written from (sampling and rotation come from info.json).
#[test]
fn commands_on_an_unedited_folder_match_the_catalog_entry() {
    let mesh = genus_surface(1, 4);
    let setup = Setup::new(&mesh);
    let cache = setup.cache();
    let folder = setup.operators("ops", "npz");
    let field = setup.path("field.txt");
    write_field(&mesh, &field);
    let constraints = setup.path("c.json");
    std::fs::write(
        &constraints,
        r#"{"constraints": [{"id": "east", "kind": "vector", "face": 12, "value": [1, 0, 0]},
            {"id": "north", "kind": "vector", "face": 100, "value": [0, 1, 0]}]}"#,
    )
    .unwrap();
    let outputs = |tag: &str, flags: &[&str]| -> [PathBuf; 3] {
        let [filtered, spline, picture] = ["filtered.txt", "spline.txt", "picture.png"]
            .map(|n| setup.path(&format!("{tag}-{n}")));
        let with = |args: Vec<&str>| {
            let mut args: Vec<String> = args.into_iter().map(String::from).collect();
            args.extend(flags.iter().map(|f| f.to_string()));
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            succeed(&cache, &args);
        };
        let field = field.to_str().unwrap();
        with(vec![
            "filter",
            &setup.mesh,
            field,
            "--integrable",
            "lowpass:t=0.05",
            "-k",
            "30",
            "-o",
            filtered.to_str().unwrap(),
        ]);
        with(vec![
            "spline",
            &setup.mesh,
            "--constraints",
            constraints.to_str().unwrap(),
            "-k",
            "30",
            "-o",
            spline.to_str().unwrap(),
        ]);
        with(vec![
            "render",
            &setup.mesh,
            field,
            "--size",
            "160x120",
            "-o",
            picture.to_str().unwrap(),
        ]);
        [filtered, spline, picture]
    };
    let ours = outputs("folder", &["--complex", &folder]);
    let catalog = outputs("catalog", &["--discretization", "conforming-barycentric"]);
    for (a, b) in ours.iter().zip(&catalog) {
        let (a_bytes, b_bytes) = (std::fs::read(a).unwrap(), std::fs::read(b).unwrap());
        assert!(!a_bytes.is_empty(), "{} is empty", a.display());
        assert_eq!(
            a_bytes,
            b_bytes,
            "{} differs from {}",
            a.display(),
            b.display()
        );
    }
}
