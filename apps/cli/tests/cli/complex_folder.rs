//! `--complex DIR` end to end: `tvf operators MESH -o DIR` (Matrix Market and `.npz`), a matrix
//! edited in the written file, and `tvf spectrum` / `tvf analyze` on the folder give the spectrum
//! of the edited matrices — checked against a dense generalized eigensolve of the two scalar
//! pencils here — twice in a row with the default cache, on a closed and an open mesh. Broken
//! folders are refused naming the file; filter, spline and render on an unedited folder give
//! the very results of the catalog entry it was written from. Generated meshes only.

use crate::common::{self, assert_success, tvf, write_field};
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
    check(&shape, "M0.mtx", "declares a 3 x 3 matrix, but each size");
    // A size of the mesh (F = 80), but not the one M0 needs.
    std::fs::write(
        Path::new(&shape).join("M0.mtx"),
        "%%MatrixMarket matrix coordinate real general\n80 80 1\n1 1 1\n",
    )
    .unwrap();
    check(
        &shape,
        "M0.mtx",
        "M0 is 80 x 80, but the complex needs 42 x 42",
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
    let outputs = |tag: &str, flags: &[&str]| -> [PathBuf; 4] {
        let [filtered, spline, picture, curl] =
            ["filtered.txt", "spline.txt", "picture.png", "curl.png"]
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
        // Face colours of potentials: the folder evaluates them by its node kinds.
        with(vec![
            "render",
            &setup.mesh,
            field,
            "--color",
            "curl",
            "--size",
            "160x120",
            "-o",
            curl.to_str().unwrap(),
        ]);
        [filtered, spline, picture, curl]
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

// ----- The sweep of hostile folders -----------------------------------------------------------

/// Copies the files of folder `from` into a new folder `to`.
fn copy_folder(from: &Path, to: &Path) {
    std::fs::create_dir(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
    }
}

/// Replaces the size line (the first line after the header and comments) of `name.mtx`.
fn size_line(dir: &Path, name: &str, line: &str) {
    let path = dir.join(format!("{name}.mtx"));
    let text = std::fs::read_to_string(&path).unwrap();
    let mut replaced = false;
    let lines: Vec<String> = text
        .lines()
        .map(|l| {
            if !replaced && !l.starts_with('%') {
                replaced = true;
                return line.to_string();
            }
            l.to_string()
        })
        .collect();
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
}

/// Replaces the file `name` of `dir` by a symbolic link to `target`.
#[cfg(unix)]
fn link_in(dir: &Path, name: &str, target: &str) {
    let _ = std::fs::remove_file(dir.join(name));
    std::os::unix::fs::symlink(target, dir.join(name)).unwrap();
}

/// Replaces the file `name` of `dir` by a FIFO nobody writes to.
fn fifo_in(dir: &Path, name: &str) {
    let _ = std::fs::remove_file(dir.join(name));
    let made = std::process::Command::new("mkfifo")
        .arg(dir.join(name))
        .status();
    assert!(made.unwrap().success());
}

/// Edits `info.json` of `dir`.
fn edit_info(dir: &Path, change: impl Fn(&mut serde_json::Value)) {
    let path = dir.join("info.json");
    let mut info: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    change(&mut info);
    std::fs::write(&path, info.to_string()).unwrap();
}

/// An `.npy` file (format 1.0) with the header dictionary `dict` and the bytes `data` as they
/// are.
fn npy_raw(dict: &str, data: &[u8]) -> Vec<u8> {
    let mut header = dict.as_bytes().to_vec();
    while !(10 + header.len() + 1).is_multiple_of(64) {
        header.push(b' ');
    }
    header.push(b'\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend(header);
    out.extend_from_slice(data);
    out
}

/// A one-dimensional little-endian `.npy` of `i8` integers or `f8` floats.
fn npy_ints(values: &[i64]) -> Vec<u8> {
    let data: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    let dict = format!(
        "{{'descr': '<i8', 'fortran_order': False, 'shape': ({},), }}",
        values.len()
    );
    npy_raw(&dict, &data)
}

/// The members of the `.npz` file `name` of `dir` (name without `.npy`, bytes).
fn npz_members(dir: &Path, name: &str) -> Vec<(String, Vec<u8>)> {
    let file = std::fs::File::open(dir.join(format!("{name}.npz"))).unwrap();
    let mut archive = zip::ZipArchive::new(file).unwrap();
    (0..archive.len())
        .map(|i| {
            let mut member = archive.by_index(i).unwrap();
            let mut bytes = Vec::new();
            std::io::Read::read_to_end(&mut member, &mut bytes).unwrap();
            (member.name().trim_end_matches(".npy").to_string(), bytes)
        })
        .collect()
}

/// Writes `members` as the `.npz` file `name` of `dir`, deflated.
fn write_npz(dir: &Path, name: &str, members: &[(String, Vec<u8>)]) {
    let file = std::fs::File::create(dir.join(format!("{name}.npz"))).unwrap();
    let mut zip = zip::ZipWriter::new(file);
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (member, bytes) in members {
        zip.start_file(format!("{member}.npy"), options).unwrap();
        std::io::Write::write_all(&mut zip, bytes).unwrap();
    }
    zip.finish().unwrap();
}

/// Replaces (or adds, or with `None` removes) members of `name.npz` in `dir`.
fn edit_npz(dir: &Path, name: &str, changes: &[(&str, Option<Vec<u8>>)]) {
    let mut members = npz_members(dir, name);
    for (member, bytes) in changes {
        members.retain(|(m, _)| m != member);
        if let Some(bytes) = bytes {
            members.push((member.to_string(), bytes.clone()));
        }
    }
    write_npz(dir, name, &members);
}

/// The data of a `.npy` member (its bytes after the header).
fn npy_payload(bytes: &[u8]) -> Vec<u8> {
    let header = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    bytes[10 + header..].to_vec()
}

/// A way to break a folder: its name, what it does to a copy of the folder, and what the
/// refusal must say (`None`: the folder is fine and must give the unbroken spectrum).
type Hostile = (&'static str, Box<dyn Fn(&Path)>, Option<&'static str>);

/// The hostile variants of a Matrix Market folder (the mesh: `icosphere(3)`, V 642, E 1920,
/// F 1280: M1 is 2560 × 2560).
#[cfg(unix)]
fn hostile_matrix_market_folders() -> Vec<Hostile> {
    let each_size = Some("each size of a matrix of this mesh");
    vec![
        (
            "M1 declares 4e9 x 4e9",
            Box::new(|d: &Path| size_line(d, "M1", "4000000000 4000000000 2560")),
            each_size,
        ),
        (
            "M1 declares 5e8 x 5e8",
            Box::new(|d: &Path| size_line(d, "M1", "500000000 500000000 2560")),
            each_size,
        ),
        (
            "M1 declares 1e12 entries",
            Box::new(|d: &Path| size_line(d, "M1", "2560 2560 1000000000000")),
            Some("holds at most"),
        ),
        (
            "M1 declares 2^64-1 entries",
            Box::new(|d: &Path| size_line(d, "M1", "2560 2560 18446744073709551615")),
            Some("holds at most"),
        ),
        (
            "M1 declares 2560 x 642",
            Box::new(|d: &Path| size_line(d, "M1", "2560 642 2560")),
            Some("column index"),
        ),
        (
            "M1.mtx links to /dev/zero",
            Box::new(|d: &Path| link_in(d, "M1.mtx", "/dev/zero")),
            Some("character device"),
        ),
        (
            "M1.mtx is a FIFO",
            Box::new(|d: &Path| fifo_in(d, "M1.mtx")),
            Some("a FIFO"),
        ),
        (
            "M1.mtx is a folder",
            Box::new(|d: &Path| {
                std::fs::remove_file(d.join("M1.mtx")).unwrap();
                std::fs::create_dir(d.join("M1.mtx")).unwrap();
            }),
            Some("a folder"),
        ),
        (
            "M1.mtx is a loop of links",
            Box::new(|d: &Path| link_in(d, "M1.mtx", "M1.mtx")),
            Some("M1"),
        ),
        (
            "info.json links to /dev/zero",
            Box::new(|d: &Path| link_in(d, "info.json", "/dev/zero")),
            Some("character device"),
        ),
        (
            "info.json is a FIFO",
            Box::new(|d: &Path| fifo_in(d, "info.json")),
            Some("a FIFO"),
        ),
        (
            "info.json is not JSON",
            Box::new(|d: &Path| std::fs::write(d.join("info.json"), "{\"sampling\": ").unwrap()),
            Some("not valid JSON"),
        ),
        (
            "info.json names ../../../../etc/passwd",
            Box::new(|d: &Path| {
                edit_info(d, |i| {
                    i["masses"]["M1"]["file"] = "../../../../etc/passwd".into()
                })
            }),
            Some("masses/M1/file"),
        ),
        (
            "info.json names /etc/passwd",
            Box::new(|d: &Path| edit_info(d, |i| i["masses"]["M1"]["file"] = "/etc/passwd".into())),
            Some("masses/M1/file"),
        ),
        (
            "info.json gives a form 'sideways'",
            Box::new(|d: &Path| edit_info(d, |i| i["masses"]["M1"]["form"] = "sideways".into())),
            Some("direct or inverse"),
        ),
        (
            "info.json calls the direct M1 an inverse file",
            Box::new(|d: &Path| {
                std::fs::rename(d.join("M1.mtx"), d.join("M1_inverse.mtx")).unwrap();
                edit_info(d, |i| {
                    i["masses"]["M1"]["file"] = "M1_inverse".into();
                    i["masses"]["M1"]["form"] = "direct".into();
                });
            }),
            Some("named as an inverse"),
        ),
        (
            "info.json calls the diagonal M1 sparse",
            Box::new(|d: &Path| edit_info(d, |i| i["masses"]["M1"]["storage"] = "sparse".into())),
            Some("holds a diagonal matrix"),
        ),
        (
            "info.json gives an unknown sampling",
            Box::new(|d: &Path| edit_info(d, |i| i["sampling"] = "nearest".into())),
            Some("sampling is 'nearest'"),
        ),
        (
            "d0.mtx is binary",
            Box::new(|d: &Path| std::fs::write(d.join("d0.mtx"), vec![0xAB; 100_000]).unwrap()),
            Some("not a Matrix Market"),
        ),
        (
            "M1.mtx has an index beyond its shape",
            Box::new(|d: &Path| {
                let path = d.join("M1.mtx");
                let text = std::fs::read_to_string(&path).unwrap() + "2561 1 1.0\n";
                std::fs::write(&path, text).unwrap();
                let entries = std::fs::read_to_string(&path)
                    .unwrap()
                    .lines()
                    .filter(|l| !l.starts_with('%'))
                    .count()
                    - 1;
                size_line(d, "M1", &format!("2560 2560 {entries}"));
            }),
            Some("row index '2561'"),
        ),
        (
            "both M1.mtx and M1.npz",
            Box::new(|d: &Path| std::fs::write(d.join("M1.npz"), b"x").unwrap()),
            Some("both M1.mtx and M1.npz"),
        ),
        (
            "vertex_map.npy links to /dev/zero",
            Box::new(|d: &Path| link_in(d, "vertex_map.npy", "/dev/zero")),
            Some("character device"),
        ),
        (
            "vertex_map.npy is a FIFO",
            Box::new(|d: &Path| fifo_in(d, "vertex_map.npy")),
            Some("a FIFO"),
        ),
        (
            "vertex_map.npy declares 1e12 entries",
            Box::new(|d: &Path| {
                std::fs::write(
                    d.join("vertex_map.npy"),
                    npy_raw(
                        "{'descr': '<i8', 'fortran_order': False, 'shape': (1000000000000,), }",
                        &[0; 64],
                    ),
                )
                .unwrap()
            }),
            Some("1000000000000 entries, 642 expected"),
        ),
        (
            "vertex_map.npy declares a 4 GiB header",
            Box::new(|d: &Path| {
                let mut bytes = b"\x93NUMPY\x02\x00".to_vec();
                bytes.extend_from_slice(&0xFFFF_FFF0u32.to_le_bytes());
                std::fs::write(d.join("vertex_map.npy"), bytes).unwrap();
            }),
            Some("header of"),
        ),
        (
            "info.json starts with a byte-order mark",
            Box::new(|d: &Path| {
                let text = std::fs::read(d.join("info.json")).unwrap();
                std::fs::write(
                    d.join("info.json"),
                    [b"\xEF\xBB\xBF".as_slice(), &text].concat(),
                )
                .unwrap();
            }),
            None,
        ),
    ]
}

/// The hostile variants of an `.npz` folder.
#[cfg(unix)]
fn hostile_npz_folders() -> Vec<Hostile> {
    let each_size = Some("each size of a matrix of this mesh");
    let shape = |rows: i64, cols: i64| Some(npy_ints(&[rows, cols]));
    vec![
        (
            "M1.npz data.npy 2-D in Fortran order",
            Box::new(|d: &Path| {
                let data = npy_payload(
                    &npz_members(d, "M1")
                        .into_iter()
                        .find(|(m, _)| m == "data")
                        .unwrap()
                        .1,
                );
                let dict = format!(
                    "{{'descr': '<f8', 'fortran_order': True, 'shape': (2, {}), }}",
                    data.len() / 16
                );
                edit_npz(d, "M1", &[("data", Some(npy_raw(&dict, &data)))]);
            }),
            Some("in Fortran order"),
        ),
        (
            "M1.npz data.npy 2-D",
            Box::new(|d: &Path| {
                let data = npy_payload(
                    &npz_members(d, "M1")
                        .into_iter()
                        .find(|(m, _)| m == "data")
                        .unwrap()
                        .1,
                );
                let dict = format!(
                    "{{'descr': '<f8', 'fortran_order': False, 'shape': ({}, 2), }}",
                    data.len() / 16
                );
                edit_npz(d, "M1", &[("data", Some(npy_raw(&dict, &data)))]);
            }),
            Some("one-dimensional"),
        ),
        (
            "M1.npz format.npy is an object array",
            Box::new(|d: &Path| {
                edit_npz(
                    d,
                    "M1",
                    &[(
                        "format",
                        Some(npy_raw(
                            "{'descr': '|O', 'fortran_order': False, 'shape': (), }",
                            &[0; 8],
                        )),
                    )],
                )
            }),
            Some("format.npy"),
        ),
        (
            "M1.npz shape (4e9, 4e9), CSR",
            Box::new(move |d: &Path| {
                edit_npz(d, "M1", &[("shape", shape(4_000_000_000, 4_000_000_000))])
            }),
            each_size,
        ),
        (
            "M1.npz shape (5e8, 5e8)",
            Box::new(move |d: &Path| {
                edit_npz(d, "M1", &[("shape", shape(500_000_000, 500_000_000))])
            }),
            each_size,
        ),
        (
            "M1.npz CSC with 4e9 rows",
            Box::new(move |d: &Path| {
                edit_npz(
                    d,
                    "M1",
                    &[
                        (
                            "format",
                            Some(npy_raw(
                                "{'descr': '|S3', 'fortran_order': False, 'shape': (), }",
                                b"csc",
                            )),
                        ),
                        ("shape", shape(4_000_000_000, 2560)),
                    ],
                )
            }),
            each_size,
        ),
        (
            "M1.npz COO (4e9, 4e9)",
            Box::new(move |d: &Path| {
                edit_npz(
                    d,
                    "M1",
                    &[
                        (
                            "format",
                            Some(npy_raw(
                                "{'descr': '|S3', 'fortran_order': False, 'shape': (), }",
                                b"coo",
                            )),
                        ),
                        ("shape", shape(4_000_000_000, 4_000_000_000)),
                        ("row", Some(npy_ints(&[0]))),
                        ("col", Some(npy_ints(&[0]))),
                    ],
                )
            }),
            each_size,
        ),
        (
            "M1.npz indices of 64M entries (deflated to about 1 MB)",
            Box::new(|d: &Path| {
                let members = npz_members(d, "M1");
                let file = std::fs::File::create(d.join("M1.npz")).unwrap();
                let mut zip = zip::ZipWriter::new(file);
                let options = zip::write::SimpleFileOptions::default()
                    .compression_method(zip::CompressionMethod::Deflated);
                for (member, bytes) in members.iter().filter(|(m, _)| m != "indices") {
                    zip.start_file(format!("{member}.npy"), options).unwrap();
                    std::io::Write::write_all(&mut zip, bytes).unwrap();
                }
                // Written a megabyte at a time: the test process stays small.
                zip.start_file("indices.npy", options).unwrap();
                let dict = "{'descr': '<i8', 'fortran_order': False, 'shape': (67108864,), }";
                std::io::Write::write_all(&mut zip, &npy_raw(dict, &[])).unwrap();
                let zeros = vec![0u8; 1 << 20];
                for _ in 0..512 {
                    std::io::Write::write_all(&mut zip, &zeros).unwrap();
                }
                zip.finish().unwrap();
                assert!(std::fs::metadata(d.join("M1.npz")).unwrap().len() < 2 << 20);
            }),
            Some("indices.npy has 67108864 entries"),
        ),
        (
            "M1.npz data.npy declares 1e12 entries",
            Box::new(|d: &Path| {
                edit_npz(
                    d,
                    "M1",
                    &[(
                        "data",
                        Some(npy_raw(
                            "{'descr': '<f8', 'fortran_order': False, 'shape': (1000000000000,), }",
                            &[0; 64],
                        )),
                    )],
                )
            }),
            Some("more than a 2560 x 2560 matrix has"),
        ),
        (
            "M1.npz indptr points past its data",
            Box::new(|d: &Path| {
                let bytes = npz_members(d, "M1")
                    .into_iter()
                    .find(|(m, _)| m == "indptr")
                    .unwrap()
                    .1;
                let mut pointers: Vec<i64> = npy_payload(&bytes)
                    .chunks(8)
                    .map(|c| i64::from_le_bytes(c.try_into().unwrap()))
                    .collect();
                *pointers.last_mut().unwrap() += 1000;
                edit_npz(d, "M1", &[("indptr", Some(npy_ints(&pointers)))]);
            }),
            Some("indptr.npy runs from"),
        ),
        (
            "M1.npz lacks indices.npy",
            Box::new(|d: &Path| edit_npz(d, "M1", &[("indices", None)])),
            Some("no member indices.npy"),
        ),
        (
            "M1.npz is text",
            Box::new(|d: &Path| std::fs::write(d.join("M1.npz"), "%%MatrixMarket\n").unwrap()),
            Some("not an .npz"),
        ),
        (
            "M1.npz links to /dev/zero",
            Box::new(|d: &Path| link_in(d, "M1.npz", "/dev/zero")),
            Some("character device"),
        ),
        (
            "M1.npz is a FIFO",
            Box::new(|d: &Path| fifo_in(d, "M1.npz")),
            Some("a FIFO"),
        ),
        (
            "M1.npz member header of 4 GiB",
            Box::new(|d: &Path| {
                let mut bytes = b"\x93NUMPY\x02\x00".to_vec();
                bytes.extend_from_slice(&0xFFFF_FFF0u32.to_le_bytes());
                edit_npz(d, "M1", &[("data", Some(bytes))]);
            }),
            Some("header of"),
        ),
        (
            "M1.npz format.npy as numpy.savez writes a str ('<U3')",
            Box::new(|d: &Path| {
                let utf32: Vec<u8> = "csr"
                    .chars()
                    .flat_map(|c| (c as u32).to_le_bytes())
                    .collect();
                edit_npz(
                    d,
                    "M1",
                    &[(
                        "format",
                        Some(npy_raw(
                            "{'descr': '<U3', 'fortran_order': False, 'shape': (), }",
                            &utf32,
                        )),
                    )],
                );
            }),
            None,
        ),
    ]
}

/// The sweep: every hostile folder (declared sizes, special files, links, names that leave the
/// folder, array layouts, byte-order marks, string members) makes `tvf spectrum` end — within
/// a minute, killed otherwise — in an error that names the folder's file and says what is wrong,
/// without a panic, an abort or an allocation failure; or, for the few that are fine (a BOM, a
/// unicode format string), in the very spectrum of the unbroken folder. No run takes more than
/// twice the memory of the unbroken run plus 32 MiB (the refused sizes would take gigabytes).
/// Special files also go through `tvf edit`, which once hung on them. Prints the counts.
#[cfg(unix)]
#[test]
fn hostile_folders_end_in_clear_errors() {
    let setup = Setup::new(&icosphere(3));
    let cache = setup.cache();
    let spectrum = |dir: &Path| {
        let dir = dir.display().to_string();
        common::output_and_peak_memory_within(
            tvf()
                .args(["spectrum", &setup.mesh, "--complex", &dir, "-k", "6"])
                .env("TVF_CACHE_DIR", &cache),
            60,
        )
    };
    let mut counts = (0, 0, 0, 0u64, 0u64);
    for (format, variants) in [
        ("mtx", hostile_matrix_market_folders()),
        ("npz", hostile_npz_folders()),
    ] {
        let good = PathBuf::from(setup.operators(&format!("good-{format}"), format));
        let (baseline, baseline_peak) = spectrum(&good);
        assert_success(&baseline);
        counts.4 = counts.4.max(baseline_peak);
        for (k, (name, make, says)) in variants.iter().enumerate() {
            let dir = setup.path(&format!("hostile-{format}-{k}"));
            copy_folder(&good, &dir);
            make(&dir);
            let (output, peak) = spectrum(&dir);
            counts.3 = counts.3.max(peak);
            let stderr = String::from_utf8_lossy(&output.stderr);
            for bad in ["panicked", "memory allocation", "RUST_BACKTRACE", "root:"] {
                assert!(!stderr.contains(bad), "{name}: {stderr}");
            }
            assert!(
                peak <= 2 * baseline_peak + 32 * 1024,
                "{name}: {peak} KiB, the unbroken folder {baseline_peak} KiB"
            );
            assert!(
                stderr.lines().all(|l| l.chars().count() < 600),
                "{name}: {stderr}"
            );
            match says {
                Some(needle) => {
                    assert_eq!(output.status.code(), Some(1), "{name}: {stderr}");
                    assert!(stderr.starts_with("error: "), "{name}: {stderr}");
                    assert!(
                        stderr.contains(&dir.display().to_string()),
                        "{name}: {stderr}"
                    );
                    assert!(stderr.contains(needle), "{name}: {stderr}");
                    counts.0 += 1;
                }
                None => {
                    assert_success(&output);
                    assert_eq!(output.stdout, baseline.stdout, "{name}");
                    counts.1 += 1;
                }
            }
            if name.contains("FIFO") || name.contains("/dev/zero") {
                let dir = dir.display().to_string();
                let (output, _) = common::output_and_peak_memory_within(
                    tvf().args([
                        "edit",
                        &setup.mesh,
                        "--complex",
                        &dir,
                        "-k",
                        "6",
                        "--no-cache",
                    ]),
                    60,
                );
                assert_eq!(output.status.code(), Some(1), "edit, {name}");
                counts.2 += 1;
            }
        }
    }
    println!(
        "sweep: {} hostile folders refused with a clear error, {} accepted with the unbroken \
         spectrum, {} edit runs on special files refused; peak memory at most {} KiB (the \
         unbroken runs: {} KiB)",
        counts.0, counts.1, counts.2, counts.3, counts.4
    );
}

/// `info.json`'s `form` is obeyed: a file holding the inverse of `M2` (the co-potential mass,
/// under a name of the user's) with `"form": "inverse"` gives the spectrum of the unedited
/// folder (the key was once ignored, and the inverse used as `M2`: a silent wrong answer).
#[test]
fn the_form_of_a_mass_in_info_json_is_obeyed() {
    let setup = Setup::new(&icosphere(2));
    let cache = setup.cache();
    let good = setup.operators("good", "mtx");
    let spectrum = |dir: &str| {
        succeed(
            &cache,
            &[
                "spectrum",
                &setup.mesh,
                "--complex",
                dir,
                "-k",
                "12",
                "--json",
            ],
        )
    };
    let expected = printed_spectrum(&spectrum(&good));
    let dir = setup.path("inverse");
    copy_folder(Path::new(&good), &dir);
    std::fs::rename(dir.join("M2.mtx"), dir.join("co-area.mtx")).unwrap();
    let folder = dir.display().to_string();
    edit(&folder, "co-area", "mtx", |_, _, value| 1.0 / value);
    edit_info(&dir, |info| {
        info["masses"]["M2"] = serde_json::json!({"file": "co-area", "form": "inverse"});
    });
    assert_close(
        &printed_spectrum(&spectrum(&folder)),
        &expected,
        "M2 given as its inverse",
    );
}
