//! DEC with intrinsic Delaunay refinement on every mesh of `../shared/meshes` (but the two
//! paper-scale `-x4` copies): `tvf info --intrinsic-delaunay=refine` reports no edge DEC would
//! refuse (every `⋆1` of the refined triangulation positive) and the harmonic dimension of the
//! mesh's topology; `tvf spectrum MESH --discretization dec-circumcentric
//! --intrinsic-delaunay=refine` and `dec-barycentric` build and find that harmonic dimension
//! (`2g` closed, `2g + b − 1` on the raw `bunny.obj`, under both boundary conditions) on every
//! mesh but the two large genus-0 scans, `bunny-closed.obj` and `armadillo.obj`: their
//! refinement is checked by `info`, their topology by `hand.obj`'s spectra, and the spectra of
//! a real scan of that size by the raw bunny's (69,451 faces).
//!
//! Uses `../shared/meshes`; skips (with a message) where that folder does not exist, and fails
//! there under `CI=true`.

use crate::common::{assert_success, tvf};
use serde_json::Value;
use std::path::Path;
use tvf_test_support::shared_meshes;

/// The meshes with their harmonic dimension (from the meshes README: genus, boundary loops) and
/// whether their spectra are computed (see the module documentation).
const MESHES: [(&str, usize, bool); 9] = [
    ("hand.obj", 0, true),
    ("rocker-arm.obj", 2, true),
    ("bunny-closed.obj", 0, false),
    ("bumpy-torus.obj", 2, true),
    ("armadillo.obj", 0, false),
    ("bunny.obj", 4, true),
    ("kitten.obj", 2, true),
    ("eight.obj", 4, true),
    ("3holes.obj", 6, true),
];

/// Eigenvalues asked for: above the largest harmonic dimension, so that the first
/// non-harmonic field shows.
const COUNT: usize = 8;

fn run_json(args: &[&str], mesh: &Path) -> Value {
    let output = tvf()
        .args(args)
        .arg(mesh)
        .args(["--json", "--quiet"])
        .output()
        .expect("the tvf binary runs");
    assert_success(&output);
    serde_json::from_slice(&output.stdout).expect("JSON on stdout")
}

/// The spectrum of `mesh` with `id` refined under `boundary` (if given): finite, ascending,
/// non-negative, with `harmonic` fields labelled harmonic.
fn check_spectrum(mesh: &Path, id: &str, boundary: Option<&str>, harmonic: usize) {
    let count = COUNT.to_string();
    let mut args = vec![
        "spectrum",
        "-k",
        &count,
        "--discretization",
        id,
        "--intrinsic-delaunay=refine",
    ];
    if let Some(condition) = boundary {
        args.extend(["--boundary", condition]);
    }
    let found = run_json(&args, mesh);
    let what = format!("{} {id} {boundary:?}", mesh.display());
    assert_eq!(
        found["discretization"].as_str().unwrap().split('+').nth(1),
        Some("intrinsic-delaunay-refine"),
        "{what}"
    );
    let labels = found["labels"].as_array().expect("labels");
    let harmonic_found = labels.iter().filter(|l| *l == "harmonic").count();
    assert_eq!(harmonic_found, harmonic, "{what}: harmonic fields");
    let values: Vec<f64> = found["eigenvalues"]
        .as_array()
        .expect("eigenvalues")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect();
    assert_eq!(values.len(), COUNT, "{what}");
    assert!(
        values.iter().all(|x| x.is_finite() && *x > -1e-8),
        "{what}: {values:?}"
    );
    assert!(
        values.windows(2).all(|w| w[0] <= w[1] + 1e-12),
        "{what}: not ascending"
    );
    assert!(values[harmonic] > 1e-6, "{what}: {values:?}");
}

#[test]
fn shared_meshes_run_refined_dec_with_the_harmonic_dimension_of_their_topology() {
    let Some(dir) = shared_meshes() else {
        return;
    };
    // Two meshes at a time: all the CI machine has (the raw bunny's three spectra, the largest
    // part, on one thread, the other spectra on the other).
    std::thread::scope(|scope| {
        for chunk in MESHES.chunks(MESHES.len().div_ceil(2)) {
            let dir = &dir;
            scope.spawn(move || {
                for &(name, harmonic, spectra) in chunk {
                    let mesh = dir.join(name);
                    let info = run_json(&["info", "--intrinsic-delaunay=refine"], &mesh);
                    let summary = &info["intrinsic_delaunay"];
                    assert_eq!(summary["not_positive_edges"], 0, "{name}: {summary}");
                    let topology = &info["harmonic_dimension"]["tangential"];
                    assert_eq!(topology.as_u64(), Some(harmonic as u64), "{name}");
                    if !spectra {
                        continue;
                    }
                    for id in ["dec-circumcentric", "dec-barycentric"] {
                        check_spectrum(&mesh, id, None, harmonic);
                    }
                    if info["closed"] == false {
                        check_spectrum(&mesh, "dec-circumcentric", Some("normal"), harmonic);
                    }
                }
            });
        }
    });
}
