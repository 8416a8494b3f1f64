//! End-to-end: `tvf operators` on built-in examples writes the five matrices of the complex and
//! the derived ones with the right shapes, `d1 d0 = 0`, symmetric `S`, and entries that match
//! the definitions, for finite elements and DEC.

use std::collections::HashMap;
use std::path::Path;
use std::process::Command;

/// A Matrix Market coordinate file as (rows, cols, entries keyed by 0-based (row, col)).
struct Market {
    rows: usize,
    cols: usize,
    entries: HashMap<(usize, usize), f64>,
}

fn read_market(path: &Path) -> Market {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().filter(|l| !l.starts_with('%'));
    let header: Vec<usize> = lines
        .next()
        .expect("size line")
        .split_whitespace()
        .map(|x| x.parse().expect("integer"))
        .collect();
    let mut entries = HashMap::new();
    for line in lines {
        let parts: Vec<&str> = line.split_whitespace().collect();
        let (i, j): (usize, usize) = (parts[0].parse().unwrap(), parts[1].parse().unwrap());
        *entries.entry((i - 1, j - 1)).or_insert(0.0) += parts[2].parse::<f64>().unwrap();
    }
    assert_eq!(entries.len(), header[2], "{}: nnz", path.display());
    Market {
        rows: header[0],
        cols: header[1],
        entries,
    }
}

fn run(example: &str, discretization: &str, out: &Path) {
    let status = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args([
            "operators",
            "--example",
            example,
            "--discretization",
            discretization,
            "--out",
        ])
        .arg(out)
        .status()
        .expect("tvf runs");
    assert!(status.success(), "tvf operators failed");
}

fn read_all(dir: &Path, names: &[&'static str]) -> HashMap<&'static str, Market> {
    names
        .iter()
        .map(|&name| (name, read_market(&dir.join(format!("{name}.mtx")))))
        .collect()
}

/// Largest entry of `a · b` (sparse, by entries).
fn product_max(a: &Market, b: &Market) -> f64 {
    let mut product: HashMap<(usize, usize), f64> = HashMap::new();
    for (&(i, k), &x) in &a.entries {
        for (&(k2, j), &y) in &b.entries {
            if k == k2 {
                *product.entry((i, j)).or_insert(0.0) += x * y;
            }
        }
    }
    product.values().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// `max |a − b|` over the union of the entries, relative to the largest entry of `a`.
fn relative_difference(a: &Market, b: &Market) -> f64 {
    assert_eq!((a.rows, a.cols), (b.rows, b.cols));
    let scale = a.entries.values().fold(0.0f64, |m, x| m.max(x.abs()));
    let keys: std::collections::HashSet<_> = a.entries.keys().chain(b.entries.keys()).collect();
    keys.into_iter()
        .map(|k| {
            let x = a.entries.get(k).copied().unwrap_or(0.0);
            let y = b.entries.get(k).copied().unwrap_or(0.0);
            (x - y).abs()
        })
        .fold(0.0f64, f64::max)
        / scale
}

const ALL: [&str; 10] = ["d0", "d1", "M0", "M1", "M2", "S0", "S2", "S", "B", "J"];

#[test]
fn writes_every_matrix_with_consistent_entries() {
    let dir = tempfile::tempdir().expect("temporary directory");
    run("torus", "conforming-barycentric", dir.path());
    let info: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("info.json")).unwrap())
            .unwrap();
    let (v, e, f) = (
        info["vertices"].as_u64().unwrap() as usize,
        info["edges"].as_u64().unwrap() as usize,
        info["faces"].as_u64().unwrap() as usize,
    );
    assert_eq!(info["discretization"], "conforming-barycentric");
    assert_eq!(info["genus"], 1);
    assert_eq!(info["harmonic_dimension"], 2);
    assert_eq!(info["nodes"]["potentials"], "vertices");
    assert_eq!(info["nodes"]["fields"], "face-frames");
    assert_eq!(info["nodes"]["co_potentials"], "edges");
    assert_eq!(v + f, e, "torus: V − E + F = 0");
    let m = read_all(dir.path(), &ALL);
    for (name, shape) in [
        ("d0", (2 * f, v)),
        ("d1", (e, 2 * f)),
        ("M0", (v, v)),
        ("M1", (2 * f, 2 * f)),
        ("M2", (e, e)),
        ("S0", (v, v)),
        ("S2", (e, e)),
        ("S", (2 * f, 2 * f)),
        ("B", (2 * f, 2 * f)),
        ("J", (2 * f, 2 * f)),
    ] {
        assert_eq!((m[name].rows, m[name].cols), shape, "{name} shape");
    }
    // Three entries per gradient row; J = [[0, −1], [1, 0]] per face; M1 = areas twice.
    assert_eq!(m["d0"].entries.len(), 6 * f);
    assert_eq!(m["J"].entries[&(0, 1)], -1.0);
    assert_eq!(m["J"].entries[&(1, 0)], 1.0);
    assert_eq!(m["M1"].entries[&(0, 0)], m["M1"].entries[&(1, 1)]);
    // d1 · d0 = 0 on a closed mesh.
    let d_scale = m["d0"].entries.values().fold(0.0f64, |a, x| a.max(x.abs()))
        * m["d1"].entries.values().fold(0.0f64, |a, x| a.max(x.abs()));
    assert!(product_max(&m["d1"], &m["d0"]) <= 1e-12 * d_scale);
    // Barycentric masses: the total area three ways (M2 is the inverse CR mass).
    let total = |name: &str| m[name].entries.values().sum::<f64>();
    let cr_area: f64 = m["M2"].entries.values().map(|x| 1.0 / x).sum();
    assert!((total("M0") - total("M1") / 2.0).abs() < 1e-12 * total("M0"));
    assert!((cr_area - total("M0")).abs() < 1e-12 * total("M0"));
    // S symmetric; S0 rows sum to zero (the gradient of a constant vanishes).
    let scale = m["S"].entries.values().fold(0.0f64, |a, x| a.max(x.abs()));
    for (&(i, j), &value) in &m["S"].entries {
        let mirror = m["S"].entries.get(&(j, i)).copied().unwrap_or(0.0);
        assert!(
            (value - mirror).abs() <= 1e-12 * scale,
            "S not symmetric at ({i},{j})"
        );
    }
    let mut row_sums = vec![0.0; v];
    for (&(i, _), &value) in &m["S0"].entries {
        row_sums[i] += value;
    }
    let s0_scale = m["S0"].entries.values().fold(0.0f64, |a, x| a.max(x.abs()));
    assert!(row_sums.iter().all(|s| s.abs() < 1e-12 * s0_scale));
}

#[test]
fn nonconforming_exchanges_the_two_function_spaces() {
    let a = tempfile::tempdir().expect("temporary directory");
    let b = tempfile::tempdir().expect("temporary directory");
    run("torus", "conforming-voronoi", a.path());
    run("torus", "nonconforming-voronoi", b.path());
    let (c, n) = (read_all(a.path(), &ALL), read_all(b.path(), &ALL));
    // The cotan matrix is the potential stiffness of one and the co-potential stiffness of the
    // other (computed as d0ᵀ M1 d0 and d1 M1⁻¹ d1ᵀ: equal to round-off); likewise CR.
    assert!(relative_difference(&c["S0"], &n["S2"]) < 1e-12);
    assert!(relative_difference(&c["S2"], &n["S0"]) < 1e-12);
    assert_eq!(
        std::fs::read_to_string(a.path().join("M1.mtx")).unwrap(),
        std::fs::read_to_string(b.path().join("M1.mtx")).unwrap(),
        "M1 must not depend on the decomposition"
    );
    assert!(
        relative_difference(&c["S"], &n["S"]) > 1e-6,
        "S differs between the decompositions"
    );
    let info = std::fs::read_to_string(b.path().join("info.json")).unwrap();
    assert!(info.contains("\"nonconforming-voronoi\""));
    // No temporary files left behind.
    let leftovers: Vec<_> = std::fs::read_dir(b.path())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty());
}

#[test]
fn dec_writes_incidences_and_the_cotan_matrix() {
    let a = tempfile::tempdir().expect("temporary directory");
    let b = tempfile::tempdir().expect("temporary directory");
    run("icosphere", "dec-barycentric", a.path());
    run("icosphere", "conforming-barycentric", b.path());
    assert!(
        !a.path().join("J.mtx").exists(),
        "1-forms have no rotation J"
    );
    let dec = read_all(a.path(), &ALL[..9]);
    let fem = read_all(b.path(), &["S0", "M0"]);
    let info: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(a.path().join("info.json")).unwrap())
            .unwrap();
    let (v, e, f) = (
        info["vertices"].as_u64().unwrap() as usize,
        info["edges"].as_u64().unwrap() as usize,
        info["faces"].as_u64().unwrap() as usize,
    );
    assert_eq!((dec["d0"].rows, dec["d0"].cols), (e, v));
    assert_eq!((dec["d1"].rows, dec["d1"].cols), (f, e));
    // Signed incidences: two ±1 per edge, three ±1 per face, and d1 d0 = 0 exactly.
    assert_eq!(dec["d0"].entries.len(), 2 * e);
    assert_eq!(dec["d1"].entries.len(), 3 * f);
    assert!(dec["d0"]
        .entries
        .values()
        .chain(dec["d1"].entries.values())
        .all(|x| x.abs() == 1.0));
    assert_eq!(product_max(&dec["d1"], &dec["d0"]), 0.0);
    // The exact eigenproblem is the cotan Laplacian with the same vertex areas.
    assert!(relative_difference(&dec["S0"], &fem["S0"]) < 1e-12);
    assert!(relative_difference(&dec["M0"], &fem["M0"]) < 1e-12);
    assert_eq!(info["nodes"]["fields"], "edges");
    assert_eq!(info["nodes"]["co_potentials"], "faces");
}

#[test]
fn bad_mesh_path_is_a_clear_error() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args([
            "operators",
            "/nonexistent/mesh.obj",
            "--discretization",
            "conforming-barycentric",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .expect("tvf runs");
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("/nonexistent/mesh.obj"), "{stderr}");
}
