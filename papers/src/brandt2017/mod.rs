//! Brandt, Scandolo, Eisemann, Hildebrandt: "Spectral Processing of Tangential Vector Fields"
//! (CGF 2017): Table 1, Figures 1, 7–11 and the time-dependent compression experiment, on the
//! paper's meshes that are present, with the basis of every mesh computed once and shared by
//! all its experiments.

pub mod report;
pub mod table1;

use crate::discretization_comparison::{self, ComparisonConfig};
use crate::registry::compared_discretizations;
use crate::step_log::StepLog;
use std::path::PathBuf;
use std::time::Instant;
use table1::{PaperTimings, Table1Repetitions, Table1Row};
use tvf_convergence::study::ConvergenceReport;
use tvf_core::io::load_mesh;
use tvf_core::SurfaceMesh;
use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};
use tvf_figures::compression::{self, RateCurve};
use tvf_figures::compression_sequence::{self, SequenceSize};
use tvf_figures::finding::{Experiment, Finding};
use tvf_figures::numbers::thousands;
use tvf_figures::panels::save;
use tvf_figures::seeded_constraints::DESIGNED_FIELD_CONSTRAINTS;
use tvf_figures::timing::Repetitions;
use tvf_figures::FigureError;
use tvf_figures::{eigenfields_and_filtering, test_fields};
use tvf_render::View;
use tvf_spectral::{compute_basis, BasisRequest, CoefficientCoding};

/// What a mesh is used for besides Table 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Figure 1 (eigenfield pairs).
    Eigenfields,
    /// Figures 7 and 8 (filtering and spectrum) and the projection timings.
    Filtering,
    /// Rate–distortion curves (Figure 9) of a designed and of an analytic smooth field.
    SmoothRateDistortion,
    /// Figure 10 and its field's rate–distortion curve (Figure 9).
    Vortices,
    /// The time-dependent compression experiment.
    Sequence,
}

/// One of the paper's meshes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperMesh {
    /// File stem in the meshes folder (`.obj`).
    pub file: &'static str,
    /// The paper's face count and Table 1 timings, if the mesh is in Table 1.
    pub paper: Option<(usize, PaperTimings)>,
    /// Only run with `--large`.
    pub large: bool,
    /// Experiments besides Table 1.
    pub roles: &'static [Role],
    /// Camera: yaw and pitch in degrees.
    pub view: (f64, f64),
}

const fn timings(
    bases: f64,
    spline: (f64, f64),
    reduced: (f64, f64),
    full: (f64, f64),
) -> PaperTimings {
    PaperTimings {
        bases,
        spline,
        reduced,
        full,
    }
}

/// The paper's meshes (the paper's Table 1). `bumpy-torus` is the public copy, coarser than the
/// paper's (31,752 instead of 140,240 faces): it runs the sequence experiment and is timed in
/// Table 1 without a ratio; `bumpy-torus-x4` (127,008 faces) is the paper-scale copy compared
/// with the paper's bumpy torus. `armadillo-x4` (345,928 faces, about 11 GB for its basis) runs
/// only with `--large`.
#[rustfmt::skip]
pub const MESHES: &[PaperMesh] = &[
    PaperMesh { file: "hand", paper: Some((12_184, timings(23.0, (0.012, 0.001), (0.148, 0.0025), (1.4, 0.016)))), large: false, roles: &[Role::Eigenfields, Role::Filtering, Role::SmoothRateDistortion], view: (-60.0, 10.0) },
    PaperMesh { file: "rocker-arm", paper: Some((20_088, timings(43.0, (0.015, 0.001), (0.148, 0.0026), (3.3, 0.028)))), large: false, roles: &[Role::SmoothRateDistortion], view: (30.0, 30.0) },
    PaperMesh { file: "bunny-closed", paper: Some((69_666, timings(184.0, (0.018, 0.002), (0.155, 0.0024), (22.7, 0.141)))), large: false, roles: &[Role::Vortices], view: (20.0, 10.0) },
    PaperMesh { file: "bumpy-torus", paper: None, large: false, roles: &[Role::Sequence], view: (20.0, 45.0) },
    PaperMesh { file: "bumpy-torus-x4", paper: Some((140_240, timings(395.0, (0.017, 0.002), (0.169, 0.0031), (86.8, 0.379)))), large: false, roles: &[], view: (20.0, 45.0) },
    PaperMesh { file: "armadillo-x4", paper: Some((331_904, timings(1246.0, (0.049, 0.004), (0.150, 0.0035), (187.7, 0.818)))), large: true, roles: &[], view: (180.0, 10.0) },
];

/// Sizes of every experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct Sizes {
    /// Eigenfield pairs of every basis (the paper: 500 + 500).
    pub pairs: usize,
    /// Constraints of the design columns (the paper: 30).
    pub constraints: usize,
    /// Repetitions of Table 1's timings.
    pub table1: Table1Repetitions,
    /// Repetitions of the projection timings.
    pub projection: Repetitions,
    /// The sequence experiment.
    pub sequence: SequenceSize,
    /// The discretization comparison.
    pub comparison: ComparisonConfig,
    /// Pixels of one panel.
    pub panel: (u32, u32),
    /// Pixels of a plot.
    pub plot: (u32, u32),
}

impl Sizes {
    /// The paper's sizes.
    pub fn paper() -> Self {
        Self {
            pairs: 500,
            constraints: 30,
            table1: Table1Repetitions {
                fast: Repetitions {
                    max: 7,
                    budget_seconds: 5.0,
                },
                full_factor: Repetitions {
                    max: 3,
                    budget_seconds: 20.0,
                },
            },
            projection: Repetitions {
                max: 5,
                budget_seconds: 5.0,
            },
            sequence: SequenceSize {
                frames: 500,
                pairs: 250,
                features: 6,
            },
            comparison: ComparisonConfig::default(),
            panel: (360, 300),
            plot: (900, 560),
        }
    }

    /// Small sizes for tests: few pairs, few frames, coarse icospheres, small pictures.
    pub fn quick() -> Self {
        Self {
            pairs: 24,
            constraints: 10,
            table1: Table1Repetitions {
                fast: Repetitions {
                    max: 3,
                    budget_seconds: 0.5,
                },
                full_factor: Repetitions {
                    max: 2,
                    budget_seconds: 0.5,
                },
            },
            projection: Repetitions {
                max: 2,
                budget_seconds: 0.5,
            },
            sequence: SequenceSize {
                frames: 6,
                pairs: 8,
                features: 2,
            },
            comparison: ComparisonConfig {
                levels: vec![1, 2, 3],
                max_degree: 3,
            },
            panel: (96, 80),
            plot: (320, 240),
        }
    }
}

/// What a run does.
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    /// Folder with the meshes (`../shared/meshes`).
    pub meshes: PathBuf,
    /// Output folder.
    pub out: PathBuf,
    /// Also run the paper-scale meshes.
    pub large: bool,
    /// Experiment sizes.
    pub sizes: Sizes,
}

/// Everything a run produced.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Results {
    /// Table 1 rows.
    pub table1: Vec<Table1Row>,
    /// Figures and experiments.
    pub findings: Vec<Finding>,
    /// The discretization comparison.
    pub comparison: ConvergenceReport,
    /// Pictures of the comparison.
    pub comparison_files: Vec<String>,
    /// Meshes not run or not finished: `(file, reason)`.
    pub skipped: Vec<(String, String)>,
    /// Machine load (`/proc/loadavg`) when each mesh started: `(what, load)`.
    pub load: Vec<(String, String)>,
    /// Wall-clock seconds of the whole run.
    pub total_seconds: f64,
}

/// The 1-, 5- and 15-minute load averages, if the system reports them.
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "unknown".to_string())
}

/// Runs every experiment on the meshes present and writes the pictures and the reports.
pub fn run(config: &Config, progress: &StepLog) -> Result<Results, FigureError> {
    let start = Instant::now();
    std::fs::create_dir_all(&config.out).map_err(|source| FigureError::Write {
        path: config.out.clone(),
        source,
    })?;
    let mut results = Results::default();
    let mut curves = Vec::new();
    for entry in MESHES.iter().filter(|m| config.large || !m.large) {
        let path = config.meshes.join(format!("{}.obj", entry.file));
        let mesh = match load_mesh(&path) {
            Ok(loaded) => loaded.mesh,
            Err(error) => {
                progress.note(format!("skipping {}: {error}", entry.file));
                results
                    .skipped
                    .push((entry.file.to_string(), error.to_string()));
                continue;
            }
        };
        // One mesh failing (e.g. a solver error) is reported, not fatal: the others still run.
        if let Err(error) = run_mesh(entry, &mesh, config, progress, &mut results, &mut curves) {
            progress.note(format!("{} failed: {error}", entry.file));
            results
                .skipped
                .push((entry.file.to_string(), format!("failed: {error}")));
        }
    }
    if !curves.is_empty() {
        let (finding, _) = progress.step("Figure 9", || {
            compression::figure9(&curves, &config.out, config.sizes.plot)
        })?;
        results.findings.push(finding);
    }
    let (comparison, _) = progress.step("discretization comparison", || {
        discretization_comparison::run(
            compared_discretizations(),
            &config.sizes.comparison,
            progress,
        )
    })?;
    let plot =
        discretization_comparison::plot(&comparison, config.sizes.plot.0, config.sizes.plot.1);
    let file = "discretization_comparison.png";
    save(&plot.render()?, &config.out.join(file))?;
    results.comparison = comparison;
    results.comparison_files.push(file.to_string());
    results.total_seconds = start.elapsed().as_secs_f64();
    Ok(results)
}

/// Table 1 and every experiment of `entry.roles` on one mesh, with one basis.
pub fn run_mesh(
    entry: &PaperMesh,
    mesh: &SurfaceMesh,
    config: &Config,
    progress: &StepLog,
    results: &mut Results,
    curves: &mut Vec<RateCurve>,
) -> Result<(), FigureError> {
    let name = entry.file;
    let sizes = &config.sizes;
    results.load.push((name.to_string(), load_average()));
    progress.note(format!(
        "{name}: {} vertices, {} faces, genus {} (load {})",
        thousands(mesh.vertex_count()),
        thousands(mesh.face_count()),
        mesh.genus(),
        load_average()
    ));
    let ((complex, basis), bases_seconds) = progress.step(
        &format!(
            "{name}: basis ({} + {} eigenfields)",
            sizes.pairs, sizes.pairs
        ),
        || {
            let complex = catalog_entry(DEFAULT_DISCRETIZATION)?.build(mesh)?;
            let basis = compute_basis(
                complex.as_ref(),
                &BasisRequest::pairs(sizes.pairs).with_seed(1),
            )?;
            Ok::<_, FigureError>((complex, basis))
        },
    )?;
    let x = Experiment {
        name,
        mesh,
        complex: complex.as_ref(),
        basis: &basis,
        out: &config.out,
        view: View {
            width: sizes.panel.0,
            height: sizes.panel.1,
            yaw: entry.view.0,
            pitch: entry.view.1,
            zoom: 1.0,
        },
    };
    let (row, _) = progress.step(&format!("{name}: Table 1 design timings"), || {
        table1::measure(
            &x,
            bases_seconds,
            sizes.constraints,
            sizes.table1,
            entry.paper,
        )
    })?;
    results.table1.push(row);
    for role in entry.roles {
        run_role(*role, &x, sizes, progress, results, curves)?;
    }
    Ok(())
}

fn run_role(
    role: Role,
    x: &Experiment,
    sizes: &Sizes,
    progress: &StepLog,
    results: &mut Results,
    curves: &mut Vec<RateCurve>,
) -> Result<(), FigureError> {
    let name = x.name;
    match role {
        Role::Eigenfields => {
            let (f, _) = progress.step(&format!("{name}: Figure 1"), || {
                eigenfields_and_filtering::figure1(x, &eigenfields_and_filtering::FIGURE1_PAIRS)
            })?;
            results.findings.push(f);
        }
        Role::Filtering => {
            let (fs, _) = progress.step(&format!("{name}: Figures 7 and 8"), || {
                eigenfields_and_filtering::figures7_8(x, sizes.plot)
            })?;
            results.findings.extend(fs);
            let field = test_fields::smooth_field(x.complex, x.mesh);
            let (f, _) = progress.step(&format!("{name}: projection timings"), || {
                compression::projection_timings(x, &field, sizes.projection)
            })?;
            results.findings.push(f);
        }
        Role::SmoothRateDistortion => {
            let (c, _) = progress.step(&format!("{name}: rate-distortion"), || {
                let designed = test_fields::designed_field(
                    x.complex,
                    x.mesh,
                    DESIGNED_FIELD_CONSTRAINTS,
                    1.0,
                    9,
                )?;
                let smooth = test_fields::smooth_field(x.complex, x.mesh);
                Ok::<_, FigureError>([
                    compression::rate_curve(
                        x,
                        &designed,
                        "designed field",
                        CoefficientCoding::Float64,
                    )?,
                    compression::rate_curve(
                        x,
                        &smooth,
                        "analytic field",
                        CoefficientCoding::Float64,
                    )?,
                ])
            })?;
            curves.extend(c);
        }
        Role::Vortices => {
            let ((f, field), _) =
                progress.step(&format!("{name}: Figure 10"), || compression::figure10(x))?;
            results.findings.push(f);
            let (c, _) = progress.step(&format!("{name}: rate-distortion"), || {
                compression::rate_curve(x, &field, "vortex field", CoefficientCoding::Float64)
            })?;
            curves.push(c);
        }
        Role::Sequence => {
            let (f, _) = progress.step(&format!("{name}: compression of a sequence"), || {
                compression_sequence::run(x, sizes.sequence)
            })?;
            results.findings.push(f);
        }
    }
    Ok(())
}
