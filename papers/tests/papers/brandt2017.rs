//! The reproduction harness on generated meshes (no files from `../shared` needed): every
//! experiment of `brandt2017` at small sizes, the reports listing every result, missing meshes
//! skipped, and the discretization comparison converging.

use tvf_core::generate::bumpy_torus;
use tvf_papers::brandt2017::report::{readme_markdown, results_markdown, write, RunInfo};
use tvf_papers::brandt2017::{
    run, run_mesh, table1, Config, PaperMesh, Results, Role, Sizes, MESHES,
};
use tvf_papers::discretization_comparison::{self, ComparisonConfig};
use tvf_papers::registry::compared_discretizations;
use tvf_papers::step_log::StepLog;

const EVERYTHING: PaperMesh = PaperMesh {
    file: "generated-bumpy-torus",
    paper: None,
    large: false,
    roles: &[
        Role::Eigenfields,
        Role::Filtering,
        Role::SmoothRateDistortion,
        Role::Vortices,
        Role::Sequence,
    ],
    view: (20.0, 45.0),
};

fn info() -> RunInfo {
    RunInfo {
        command: "tvf-papers brandt2017 --meshes M --out O".to_string(),
        threads: 1,
    }
}

#[test]
fn every_experiment_runs_on_a_generated_mesh_and_the_reports_list_every_result() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = bumpy_torus(1.0, 0.35, 40, 20, 6, 0.3).unwrap();
    let mut sizes = Sizes::quick();
    sizes.comparison.levels = vec![1, 2];
    let config = Config {
        meshes: dir.path().join("none"),
        out: dir.path().to_path_buf(),
        large: false,
        sizes,
    };
    let progress = StepLog::new(true);
    let mut results = Results::default();
    let mut curves = Vec::new();
    let mut entry = EVERYTHING;
    let paper = MESHES[0].paper;
    entry.paper = paper;
    run_mesh(
        &entry,
        &mesh.clone().into(),
        &config,
        &progress,
        &mut results,
        &mut curves,
    )
    .unwrap();
    assert_eq!(
        curves.len(),
        3,
        "designed, analytic and vortex rate-distortion curves"
    );
    for curve in &curves {
        // The error of a truncated Fourier series cannot grow with more pairs.
        for w in curve.points.windows(2) {
            assert!(w[1].relative_error <= w[0].relative_error + 1e-12);
        }
    }
    results
        .findings
        .push(tvf_figures::compression::figure9(&curves, dir.path(), (320, 240)).unwrap());

    // Table 1: one row, every column measured, the paper's numbers beside ours.
    let row = &results.table1[0];
    assert_eq!(row.faces, mesh.face_count());
    assert_eq!(row.constraints, 10);
    assert!(row.bases > 0.0 && row.spline_setup.median > 0.0 && row.full_factor.median > 0.0);
    assert!(
        row.spline_residual < 1e-6,
        "hard constraints hold: {}",
        row.spline_residual
    );
    assert!(row.full_residual < 1e-8);
    let table = table1::markdown(&results.table1);
    let header = table.lines().next().unwrap();
    for column in [
        "bases setup",
        "spline setup",
        "spline solve",
        "reduced soft factor",
        "reduced soft solve",
        "full soft factor",
        "full soft solve",
    ] {
        assert!(header.contains(column), "missing column {column}");
    }
    let data = table.lines().nth(2).unwrap();
    assert_eq!(data.matches("(23.00 s, ×").count(), 1, "{data}");
    assert_eq!(
        data.matches(", ×").count(),
        7,
        "paper/ours in every timing: {data}"
    );

    // Every finding has its pictures on disk.
    let ids: Vec<&str> = results.findings.iter().map(|f| f.id.as_str()).collect();
    for id in [
        "Figure 1",
        "Figure 7",
        "Figure 8",
        "Figure 9",
        "Figure 10",
        "Section 8.6 timings",
        "Section 8.6 / Figure 11",
    ] {
        assert!(ids.contains(&id), "missing {id} in {ids:?}");
    }
    for f in &results.findings {
        for file in &f.files {
            let bytes = std::fs::metadata(dir.path().join(file)).unwrap().len();
            assert!(bytes > 1000, "{file} is {bytes} bytes");
        }
        assert!(!f.paper.is_empty() && !f.comparison.is_empty(), "{}", f.id);
    }

    // The reports list every result and every file.
    write(dir.path(), &results, &info()).unwrap();
    let readme = std::fs::read_to_string(dir.path().join("README.md")).unwrap();
    let full = std::fs::read_to_string(dir.path().join("RESULTS.md")).unwrap();
    assert_eq!(readme, readme_markdown(&results, &info()));
    assert_eq!(full, results_markdown(&results, &info()));
    assert!(readme.contains("Table 1"));
    for f in &results.findings {
        assert!(readme.contains(&f.id), "README misses {}", f.id);
        assert!(
            full.contains(&format!("## {}", f.id)),
            "RESULTS misses {}",
            f.id
        );
        for file in &f.files {
            assert!(readme.contains(file.as_str()) && full.contains(file.as_str()));
        }
    }
    assert!(full.contains("generated-bumpy-torus"));
}

#[test]
fn missing_and_failing_meshes_are_skipped_and_the_comparison_still_runs() {
    let dir = tempfile::tempdir().unwrap();
    // A hand that loads but has a boundary: its basis fails, the run goes on.
    let meshes = dir.path().join("meshes");
    std::fs::create_dir_all(&meshes).unwrap();
    std::fs::write(
        meshes.join("hand.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
    )
    .unwrap();
    let mut sizes = Sizes::quick();
    sizes.comparison = ComparisonConfig {
        levels: vec![1, 2],
        max_degree: 2,
    };
    let config = Config {
        meshes,
        out: dir.path().join("out"),
        large: false,
        sizes,
    };
    let results = run(&config, &StepLog::new(true)).unwrap();
    let default_meshes = MESHES.iter().filter(|m| !m.large).count();
    assert_eq!(results.skipped.len(), default_meshes);
    let (mesh, reason) = &results.skipped[0];
    assert_eq!(mesh, "hand");
    assert!(reason.starts_with("failed:"), "{reason}");
    assert!(results.table1.is_empty() && results.findings.is_empty());
    assert_eq!(
        results.comparison.orders.len(),
        2 * compared_discretizations().len()
    );
    write(&config.out, &results, &info()).unwrap();
    let full = std::fs::read_to_string(config.out.join("RESULTS.md")).unwrap();
    for (mesh, _) in &results.skipped {
        assert!(full.contains(mesh.as_str()));
    }
    assert!(full.contains("## Discretization comparison"));
    assert!(config.out.join("discretization_comparison.png").exists());
}

#[test]
fn every_discretization_converges_on_icospheres() {
    let config = ComparisonConfig {
        levels: vec![1, 2, 3],
        max_degree: 3,
    };
    let report =
        discretization_comparison::run(compared_discretizations(), &config, &StepLog::new(true))
            .unwrap();
    assert_eq!(report.rows.len(), 3 * compared_discretizations().len());
    for entry in compared_discretizations() {
        let rows: Vec<_> = report
            .rows
            .iter()
            .filter(|r| r.discretization == entry.id())
            .collect();
        assert_eq!(rows.len(), 3);
        for w in rows.windows(2) {
            assert!(
                w[1].integrable_error < w[0].integrable_error,
                "{}",
                entry.id()
            );
            assert!(
                w[1].cointegrable_error < w[0].cointegrable_error,
                "{}",
                entry.id()
            );
        }
    }
    for order in &report.orders {
        assert!(order.order > 0.5, "{order:?}");
    }
    // Conforming and nonconforming share their spectra with the families swapped.
    let rows_of = |id: &str| {
        report
            .rows
            .iter()
            .filter(|r| r.discretization == id)
            .collect::<Vec<_>>()
    };
    let (c, n) = (
        rows_of("conforming-barycentric"),
        rows_of("nonconforming-barycentric"),
    );
    assert_eq!(c.len(), 3);
    for (a, b) in c.iter().zip(&n) {
        assert!(
            (a.integrable_error - b.cointegrable_error).abs() < 1e-8 * (1.0 + a.integrable_error)
        );
    }
}
