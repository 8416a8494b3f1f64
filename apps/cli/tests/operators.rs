//! End-to-end: `tvf operators` on a built-in example writes every matrix with the right shape,
//! symmetric `S`, and entries that match the definitions.

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

fn run(decomposition: &str, mass: &str, out: &Path) {
    let status = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args([
            "operators",
            "--example",
            "torus",
            "--decomposition",
            decomposition,
            "--mass",
            mass,
            "--out",
        ])
        .arg(out)
        .status()
        .expect("tvf runs");
    assert!(status.success(), "tvf operators failed");
}

#[test]
fn writes_every_matrix_with_consistent_entries() {
    let dir = tempfile::tempdir().expect("temporary directory");
    run("conforming", "barycentric", dir.path());
    let info: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("info.json")).unwrap())
            .unwrap();
    let (v, e, f) = (
        info["vertices"].as_u64().unwrap() as usize,
        info["edges"].as_u64().unwrap() as usize,
        info["faces"].as_u64().unwrap() as usize,
    );
    assert_eq!(info["genus"], 1);
    assert_eq!(info["harmonic_dimension"], 2);
    assert_eq!(v + f, e, "torus: V − E + F = 0");
    let m: HashMap<&str, Market> = [
        "G", "Gstar", "M", "Mstar", "MX", "J", "Sc", "Sstar", "S", "B",
    ]
    .into_iter()
    .map(|name| (name, read_market(&dir.path().join(format!("{name}.mtx")))))
    .collect();
    for (name, shape) in [
        ("G", (2 * f, v)),
        ("Gstar", (2 * f, e)),
        ("M", (v, v)),
        ("Mstar", (e, e)),
        ("MX", (2 * f, 2 * f)),
        ("J", (2 * f, 2 * f)),
        ("Sc", (v, v)),
        ("Sstar", (e, e)),
        ("S", (2 * f, 2 * f)),
        ("B", (2 * f, 2 * f)),
    ] {
        assert_eq!((m[name].rows, m[name].cols), shape, "{name} shape");
    }
    // Three entries per gradient row; J = [[0, −1], [1, 0]] per face; MX = areas twice.
    assert_eq!(m["G"].entries.len(), 6 * f);
    assert_eq!(m["Gstar"].entries.len(), 6 * f);
    assert_eq!(m["J"].entries[&(0, 1)], -1.0);
    assert_eq!(m["J"].entries[&(1, 0)], 1.0);
    assert_eq!(m["MX"].entries[&(0, 0)], m["MX"].entries[&(1, 1)]);
    // Barycentric masses: total area three ways.
    let total = |name: &str| m[name].entries.values().sum::<f64>();
    assert!((total("M") - total("MX") / 2.0).abs() < 1e-12 * total("M"));
    assert!((total("Mstar") - total("M")).abs() < 1e-12 * total("M"));
    // S symmetric; Sc rows sum to zero; Gstar = −2 G per face, column-wise: the CR gradient
    // of the edge opposite a corner equals −2 × that corner's hat gradient, so each Gstar row sums
    // to −2 × the G row sum, which is 0 (gradients of a partition of unity).
    let scale = m["S"].entries.values().fold(0.0f64, |a, x| a.max(x.abs()));
    for (&(i, j), &value) in &m["S"].entries {
        let mirror = m["S"].entries.get(&(j, i)).copied().unwrap_or(0.0);
        assert!(
            (value - mirror).abs() <= 1e-12 * scale,
            "S not symmetric at ({i},{j})"
        );
    }
    let mut row_sums = vec![0.0; v];
    for (&(i, _), &value) in &m["Sc"].entries {
        row_sums[i] += value;
    }
    let sc_scale = m["Sc"].entries.values().fold(0.0f64, |a, x| a.max(x.abs()));
    assert!(row_sums.iter().all(|s| s.abs() < 1e-12 * sc_scale));
    for row in 0..2 * f {
        let g: f64 = (0..v).filter_map(|c| m["G"].entries.get(&(row, c))).sum();
        let gs: f64 = (0..e)
            .filter_map(|c| m["Gstar"].entries.get(&(row, c)))
            .sum();
        assert!(
            g.abs() < 1e-9 && gs.abs() < 1e-9,
            "gradient of a constant is not zero"
        );
    }
}

#[test]
fn nonconforming_differs_only_in_field_matrices() {
    let a = tempfile::tempdir().expect("temporary directory");
    let b = tempfile::tempdir().expect("temporary directory");
    run("conforming", "voronoi", a.path());
    run("nonconforming", "voronoi", b.path());
    for name in ["G", "Gstar", "M", "Mstar", "MX", "J", "Sc", "Sstar"] {
        let x = std::fs::read_to_string(a.path().join(format!("{name}.mtx"))).unwrap();
        let y = std::fs::read_to_string(b.path().join(format!("{name}.mtx"))).unwrap();
        assert_eq!(x, y, "{name} must not depend on the decomposition");
    }
    let s_conforming = std::fs::read_to_string(a.path().join("S.mtx")).unwrap();
    let s_nonconforming = std::fs::read_to_string(b.path().join("S.mtx")).unwrap();
    assert_ne!(
        s_conforming, s_nonconforming,
        "S differs between the decompositions"
    );
    let info = std::fs::read_to_string(b.path().join("info.json")).unwrap();
    assert!(info.contains("\"nonconforming\"") && info.contains("\"voronoi\""));
    // No temporary files left behind.
    let leftovers: Vec<_> = std::fs::read_dir(b.path())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty());
}

#[test]
fn bad_mesh_path_is_a_clear_error() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let output = Command::new(env!("CARGO_BIN_EXE_tvf"))
        .args([
            "operators",
            "/nonexistent/mesh.obj",
            "--decomposition",
            "conforming",
            "--out",
        ])
        .arg(dir.path())
        .output()
        .expect("tvf runs");
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("/nonexistent/mesh.obj"), "{stderr}");
}
