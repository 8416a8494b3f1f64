//! End-to-end: the example binary runs tvf's commands on its own entry `blend-lumping-50` (a
//! generated genus-1 mesh written as OBJ; a disk for the boundary conditions): the listing,
//! the matrices (`M0` the blend of the two built-in lumpings'), the spectrum, a basis file that
//! reopens with `--basis`, filters, a spline, and the editor over HTTP.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use tvf_core::generate::{disk, genus_surface};
use tvf_core::io::write_obj;
use tvf_test_support::{request, EditorProcess};

const ENTRY: &str = "blend-lumping-50";

/// The example's command line, with the user's cache folder (the default basis cache) in the
/// tests' temporary folder rather than the home folder.
fn example() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_tvf-example-own-discretization"));
    command.env(
        "XDG_CACHE_HOME",
        Path::new(env!("CARGO_TARGET_TMPDIR")).join("xdg-cache"),
    );
    command
}

/// Runs the example with `args`; fails the test with its stderr unless it succeeded.
#[track_caller]
fn run(args: &[&str]) -> Output {
    let output = example().args(args).output().expect("the example runs");
    assert!(
        output.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// A folder with the genus-1 test mesh as `ring.obj`; returns the folder and the mesh path.
fn ring() -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ring.obj");
    write_obj(&path, &genus_surface(1, 4)).unwrap();
    let path = path.display().to_string();
    (dir, path)
}

fn json(output: &Output) -> serde_json::Value {
    serde_json::from_slice(&output.stdout).expect("JSON on stdout")
}

#[test]
fn the_listing_has_the_own_entries_after_the_built_in_ones() {
    let listing = json(&run(&["discretizations", "--json"]));
    let ids: Vec<&str> = listing["discretizations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["id"].as_str().unwrap())
        .collect();
    let builtin: Vec<&str> = tvf_discretizations::builtin_catalog().ids().collect();
    assert_eq!(ids.len(), builtin.len() + 4, "{ids:?}");
    assert_eq!(&ids[..builtin.len()], builtin.as_slice());
    assert_eq!(
        &ids[builtin.len()..],
        [
            "blend-lumping-25",
            "blend-lumping-50",
            "blend-lumping-75",
            "dec-length-star"
        ]
    );
    let entry = &listing["discretizations"][builtin.len() + 1];
    assert_eq!(
        entry["boundary_conditions"],
        serde_json::json!(["tangential", "normal"])
    );
    let text = String::from_utf8(run(&["discretizations"]).stdout).unwrap();
    assert!(
        text.contains("blend-lumping-50 — the conforming decomposition with lumped masses 0.50"),
        "{text}"
    );
}

#[test]
fn an_unknown_id_is_a_usage_error_listing_the_own_entries() {
    let output = example()
        .args([
            "spectrum",
            "--example",
            "torus",
            "-k",
            "4",
            "--discretization",
            "blend-lumping-51",
        ])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("unknown discretization 'blend-lumping-51'")
            && stderr.contains("blend-lumping-50, blend-lumping-75"),
        "{stderr}"
    );
}

/// The diagonal of the Matrix Market file `path` (a diagonal matrix, `coordinate real`).
fn diagonal(path: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('%'));
    let size: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    let mut values = vec![0.0; size[0]];
    for line in lines {
        let parts: Vec<&str> = line.split_whitespace().collect();
        let (i, j): (usize, usize) = (parts[0].parse().unwrap(), parts[1].parse().unwrap());
        assert_eq!(i, j, "{}: not diagonal", path.display());
        values[i - 1] = parts[2].parse().unwrap();
    }
    values
}

#[test]
fn operators_have_the_blended_mass() {
    let (dir, mesh) = ring();
    let m0 = |id: &str| {
        let out = dir.path().join(id);
        run(&[
            "operators",
            &mesh,
            "--discretization",
            id,
            "-o",
            out.to_str().unwrap(),
        ]);
        diagonal(&out.join("M0.mtx"))
    };
    let blend = m0(ENTRY);
    let barycentric = m0("conforming-barycentric");
    let voronoi = m0("conforming-voronoi");
    assert!(barycentric
        .iter()
        .zip(&voronoi)
        .any(|(b, v)| (b - v).abs() > 1e-6 * b));
    for ((m, b), v) in blend.iter().zip(&barycentric).zip(&voronoi) {
        let expected = 0.5 * (b + v);
        assert!(
            (m - expected).abs() <= 1e-12 * expected,
            "{m} against {expected}"
        );
    }
}

/// The eigenvalues of `tvf spectrum --json` for `id` on `mesh`.
fn spectrum(mesh: &str, id: &str, extra: &[&str]) -> Vec<f64> {
    let mut args = vec![
        "spectrum",
        mesh,
        "-k",
        "12",
        "--discretization",
        id,
        "--json",
        "-q",
    ];
    args.extend_from_slice(extra);
    let report = json(&run(&args));
    report["eigenvalues"]
        .as_array()
        .unwrap_or_else(|| panic!("no eigenvalues in {report}"))
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

#[test]
fn spectrum_lies_between_the_two_lumpings_and_offers_both_boundary_conditions() {
    let (_dir, mesh) = ring();
    let blend = spectrum(&mesh, ENTRY, &[]);
    let barycentric = spectrum(&mesh, "conforming-barycentric", &[]);
    let voronoi = spectrum(&mesh, "conforming-voronoi", &[]);
    assert_eq!(blend.len(), 12);
    // Two harmonic fields on the torus, then positive eigenvalues, sorted.
    assert!(blend[..2].iter().all(|l| l.abs() < 1e-8), "{blend:?}");
    assert!(blend[2..].windows(2).all(|w| w[0] <= w[1] + 1e-12) && blend[2] > 1e-6);
    // Neither built-in spectrum, but close to both (the masses differ by a few per cent).
    for other in [&barycentric, &voronoi] {
        let gap = blend[2..]
            .iter()
            .zip(&other[2..])
            .map(|(a, b)| (a - b).abs() / b)
            .fold(0.0, f64::max);
        assert!(
            gap > 1e-6 && gap < 0.2,
            "{gap}: {blend:?} against {other:?}"
        );
    }
    // On a disk, both boundary conditions of the entry.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("disk.obj");
    write_obj(&path, &disk(4)).unwrap();
    let path = path.display().to_string();
    let tangential = spectrum(&path, ENTRY, &["--boundary", "tangential"]);
    let normal = spectrum(&path, ENTRY, &["--boundary", "normal"]);
    assert_ne!(tangential, normal);
}

/// Writes `faces` smooth face vectors as a text field file.
fn write_field(path: &Path, faces: usize) {
    let text: String = (0..faces)
        .map(|t| {
            let x = t as f64 * 0.1;
            format!(
                "{} {} {}\n",
                x.sin(),
                (0.7 * x).cos(),
                0.3 * (1.3 * x).sin()
            )
        })
        .collect();
    std::fs::write(path, text).unwrap();
}

/// The face vectors of a field file, flattened (`3F` values).
fn read_field(path: &Path) -> Vec<f64> {
    tvf_spectral::read_face_vectors(path)
        .unwrap()
        .into_iter()
        .flatten()
        .collect()
}

#[test]
fn a_basis_file_reopens_with_the_own_entry_and_filters_with_it() {
    let (dir, mesh) = ring();
    let faces = genus_surface(1, 4).face_count();
    let basis = dir.path().join("b.tvfb");
    let basis = basis.to_str().unwrap();
    run(&[
        "-q",
        "basis",
        &mesh,
        "-k",
        "30",
        "--discretization",
        ENTRY,
        "-o",
        basis,
    ]);
    let header = tvf_spectral::read_basis_header(Path::new(basis)).unwrap();
    assert_eq!(header.key.discretization, ENTRY);

    let field = dir.path().join("field.txt");
    write_field(&field, faces);
    let field = field.to_str().unwrap();
    // Identity filter through the reopened basis: the field comes back (rest included).
    let same = dir.path().join("same.txt");
    run(&[
        "-q",
        "filter",
        &mesh,
        field,
        "--basis",
        basis,
        "-o",
        same.to_str().unwrap(),
    ]);
    let twice = dir.path().join("twice.txt");
    run(&[
        "-q",
        "filter",
        &mesh,
        same.to_str().unwrap(),
        "--basis",
        basis,
        "-o",
        twice.to_str().unwrap(),
    ]);
    let (a, b) = (read_field(&same), read_field(&twice));
    assert_eq!(a.len(), 3 * faces);
    let error = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(error < 1e-10, "{error}");
    // A low-pass with a computed basis (cached in the user's cache folder) keeps fewer
    // frequencies.
    let smooth = dir.path().join("smooth.txt");
    let report = json(&run(&[
        "-q",
        "filter",
        &mesh,
        field,
        "-k",
        "30",
        "--discretization",
        ENTRY,
        "--integrable",
        "lowpass:t=0.5",
        "--cointegrable",
        "lowpass:t=0.5",
        "--rest",
        "0",
        "-o",
        smooth.to_str().unwrap(),
        "--json",
    ]));
    assert!(report.to_string().contains(ENTRY), "{report}");
    let smooth = read_field(&smooth);
    assert!(smooth.iter().all(|x| x.is_finite()));
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(norm(&smooth) < norm(&a), "the low-pass removes energy");
    // The basis is refused for another entry, naming both.
    let output = example()
        .args([
            "filter",
            &mesh,
            field,
            "--basis",
            basis,
            "--discretization",
            "blend-lumping-25",
            "-o",
        ])
        .arg(dir.path().join("x.txt"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !output.status.success() && stderr.contains(ENTRY) && stderr.contains("blend-lumping-25"),
        "{stderr}"
    );
}

const CONSTRAINTS: &str = r#"{"omega": 0.1, "constraints": [
  {"id": "east", "kind": "vector", "face": 12, "value": [1, 0, 0]},
  {"id": "source", "kind": "divergence", "vertex": 40, "value": 2.0},
  {"id": "vortex", "kind": "curl", "face": 150, "barycentric": [0.3, 0.3, 0.4], "value": 1.0}]}"#;

#[test]
fn a_spline_meets_its_constraints_with_the_own_entry() {
    let (dir, mesh) = ring();
    let constraints = dir.path().join("c.json");
    std::fs::write(&constraints, CONSTRAINTS).unwrap();
    let out = dir.path().join("spline.txt");
    let report = json(&run(&[
        "-q",
        "spline",
        &mesh,
        "--constraints",
        constraints.to_str().unwrap(),
        "-k",
        "60",
        "--discretization",
        ENTRY,
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(report["discretization"], ENTRY, "{report}");
    let worst = report["worst_relative_residual"].as_f64().unwrap();
    assert!(worst < 1e-8, "{report}");
    assert_eq!(read_field(&out).len(), 3 * genus_surface(1, 4).face_count());
}

#[test]
fn the_editor_edits_with_the_own_entry() {
    let (dir, mesh) = ring();
    let cache: PathBuf = dir.path().join("cache");
    let mut command = example();
    command
        .args([
            "-q",
            "edit",
            &mesh,
            "-k",
            "40",
            "--discretization",
            ENTRY,
            "--cache-dir",
        ])
        .arg(&cache);
    let server = EditorProcess::start(command);
    assert!(
        server.printed.join("\n").contains(ENTRY),
        "{:?}",
        server.printed
    );
    let (address, token) = (server.address.as_str(), server.token.as_str());
    let (code, frame) = request(
        address,
        "POST",
        "/api/edit",
        token,
        r#"{"op": "add", "constraint": {"id": "v", "kind": "vector", "face": 100, "value": [0.3, 1.0, -0.2]}}"#,
    );
    assert_eq!(code, 200, "{}", String::from_utf8_lossy(&frame));
    let (code, check) = request(address, "GET", "/api/check", token, "");
    assert_eq!(code, 200);
    let check: serde_json::Value = serde_json::from_slice(&check).unwrap();
    assert_eq!(check["constraints"].as_array().unwrap().len(), 1, "{check}");
    assert!(check["max_relative"].as_f64().unwrap() < 1e-9, "{check}");
    drop(server);
}

/// `check` with the DEC-like entry of this crate: the core checks and the accuracy checks
/// (consistency on patches, convergence on the sphere and hemisphere) pass, the convergence
/// orders reported at least 1.5.
#[test]
fn the_dec_like_entry_passes_check_with_its_accuracy_checks() {
    let output = run(&[
        "check",
        "--example",
        "icosphere",
        "--discretization",
        "dec-length-star",
        "--json",
    ]);
    let report = json(&output);
    assert_eq!(report["passed"], true);
    let orders: Vec<f64> = report["checks"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["name"].as_str().unwrap().starts_with("convergence:"))
        .map(|c| c["measured"].as_f64().unwrap())
        .collect();
    assert_eq!(orders.len(), 8, "two families on four sequences");
    assert!(orders.iter().all(|&p| p >= 1.5), "{orders:?}");
}

/// `compare` takes this crate's entries like tvf's own: on the icosphere the DEC-like entry
/// against `dec-circumcentric` (both spectra near the sphere's, the l = 1, 2 eigenspaces at
/// small angles), and over a folder on local threads with the blended entry.
#[test]
fn compare_takes_the_own_entries_on_one_mesh_and_over_a_folder() {
    let report = json(&run(&[
        "compare",
        "--example",
        "icosphere",
        "-k",
        "16",
        "--discretization",
        "dec-circumcentric",
        "--discretization",
        "dec-length-star",
        "--json",
        "--quiet",
    ]));
    let own = &report["entries"][1];
    assert_eq!(own["discretization"], "dec-length-star");
    let angles: Vec<f64> = own["principal_angles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_f64().unwrap())
        .collect();
    assert_eq!(angles.len(), 16);
    assert!(
        angles.iter().all(|&a| (0.0..0.2).contains(&a)),
        "{angles:?}"
    );
    let (dir, _) = ring();
    let folder = dir.path().display().to_string();
    let corpus = json(&run(&[
        "compare",
        "--corpus",
        &folder,
        "-k",
        "8",
        "--discretization",
        "conforming-barycentric",
        "--discretization",
        ENTRY,
        "--json",
        "--quiet",
    ]));
    let entries = corpus["entries"].as_array().unwrap();
    assert_eq!(entries[1]["discretization"], ENTRY);
    assert_eq!(entries[1]["succeeded"], 1, "{corpus}");
    let difference = entries[1]["median_relative_difference"].as_f64().unwrap();
    assert!(difference > 0.0 && difference < 0.2, "{difference}");
}
