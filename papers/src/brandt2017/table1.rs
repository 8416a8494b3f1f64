//! Table 1 of the paper: time to compute the basis (500 + 500 eigenfields), and setup / solve
//! of the reduced spline, the reduced soft design and the full soft design with 30 seeded
//! constraints, beside the paper's numbers (Java + MUMPS on a 2015 laptop).

use crate::markdown::Table;
use tvf_core::discretization::HodgeOperators;
use tvf_design::{
    default_regularization, ConstraintAssembler, FullSoftDesign, ReducedBasis, ReducedSoftDesign,
    SoftOptions, SplineSession, DEFAULT_OMEGA,
};
use tvf_figures::finding::Experiment;
use tvf_figures::numbers::{ratio, seconds, thousands};
use tvf_figures::seeded_constraints::seeded_constraints;
use tvf_figures::timing::{median_time, Repetitions, Timing};
use tvf_figures::FigureError;

/// The paper's timings of one mesh (seconds).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperTimings {
    /// Bases setup.
    pub bases: f64,
    /// Spline editing setup and solve.
    pub spline: (f64, f64),
    /// Reduced soft design factor and solve.
    pub reduced: (f64, f64),
    /// Full soft design factor and solve.
    pub full: (f64, f64),
}

/// How often the timed operations are repeated (medians are reported).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Table1Repetitions {
    /// The fast operations (spline, reduced soft design, full solve).
    pub fast: Repetitions,
    /// The full soft-design factorization.
    pub full_factor: Repetitions,
}

/// One row of Table 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Table1Row {
    /// Mesh name.
    pub mesh: String,
    /// Vertices.
    pub vertices: usize,
    /// Faces.
    pub faces: usize,
    /// The paper's face count for this mesh (if it is one of the paper's).
    pub paper_faces: Option<usize>,
    /// Fields in the basis (harmonic included).
    pub basis_fields: usize,
    /// Seconds to assemble the complex and compute the basis (one run).
    pub bases: f64,
    /// Number of constraints.
    pub constraints: usize,
    /// Spline session with every constraint added.
    pub spline_setup: Timing,
    /// Reduced spline solve (coefficients).
    pub spline_solve: Timing,
    /// Mapping the coefficients to the full field, `x = U v` (in the paper's solve, on the GPU).
    pub map: Timing,
    /// Largest constraint residual of the spline field (hard constraints: ≈ 0).
    pub spline_residual: f64,
    /// Reduced soft design: system with every constraint (dense Cholesky, rank updates).
    pub reduced_factor: Timing,
    /// Reduced soft design solve.
    pub reduced_solve: Timing,
    /// Full soft design: assembly and sparse factorization (given `S`).
    pub full_factor: Timing,
    /// Full soft design solve (with iterative refinement).
    pub full_solve: Timing,
    /// Relative residual `‖b − Ax‖/‖b‖` of the full solve.
    pub full_residual: f64,
    /// Its rounding floor ([`tvf_design::SolveReport::rounding_floor`]): how much changing the
    /// field's entries in their last bit moves the residual.
    pub full_rounding_floor: f64,
    /// The paper's numbers.
    pub paper: Option<PaperTimings>,
}

/// Measures the design columns of Table 1 on the mesh of `x` with its basis (whose time,
/// `bases_seconds`, the caller measured), with `constraint_count` seeded constraints.
pub fn measure(
    x: &Experiment,
    bases_seconds: f64,
    constraint_count: usize,
    repetitions: Table1Repetitions,
    paper: Option<(usize, PaperTimings)>,
) -> Result<Table1Row, FigureError> {
    let (mesh, complex, basis) = (x.mesh, x.complex, x.basis);
    let constraints = seeded_constraints(mesh, complex, constraint_count, 30);
    let compiled = ConstraintAssembler::new(complex, mesh).compile_all(&constraints)?;
    let reduced = ReducedBasis::from_spectral(basis)?;
    let fast = repetitions.fast;

    let (spline_setup, session) = median_time(fast, || {
        let mut session = SplineSession::new(&reduced, DEFAULT_OMEGA)?;
        for c in &compiled {
            session.add(c.clone())?;
        }
        Ok::<_, FigureError>(session)
    })?;
    let (spline_solve, v) = median_time(fast, || Ok::<_, FigureError>(session.solve()))?;
    let mut field = vec![0.0; reduced.field_dimension()];
    let (map, ()) = median_time(fast, || reduced.map(&v, &mut field))?;
    let spline_residual = session
        .residuals(&field)
        .iter()
        .map(|r| r.relative)
        .fold(0.0, f64::max);
    drop(session);

    // S is formed now, so that the full factorization below is timed given S (as in the paper).
    // With non-diagonal masses S is composed, and the sparse blocks of the augmented system are
    // assembled inside the timed factorization.
    complex.dirichlet_energy();
    let options = SoftOptions {
        omega: DEFAULT_OMEGA,
        regularization: default_regularization(complex),
    };
    let (reduced_factor, design) = median_time(fast, || {
        let mut design = ReducedSoftDesign::new(&reduced, options)?;
        design.add_all(compiled.iter().cloned())?;
        Ok::<_, FigureError>(design)
    })?;
    let (reduced_solve, _) = median_time(fast, || Ok::<_, FigureError>(design.solve()))?;
    drop(design);
    drop(reduced);

    let (full_factor, full) = median_time(repetitions.full_factor, || {
        FullSoftDesign::new(complex, options, compiled.clone())
    })?;
    let (full_solve, (_, report)) = median_time(fast, || Ok::<_, FigureError>(full.solve()))?;

    Ok(Table1Row {
        mesh: x.name.to_string(),
        vertices: mesh.vertex_count(),
        faces: mesh.face_count(),
        paper_faces: paper.map(|p| p.0),
        basis_fields: basis.len(),
        bases: bases_seconds,
        constraints: compiled.len(),
        spline_setup,
        spline_solve,
        map,
        spline_residual,
        reduced_factor,
        reduced_solve,
        full_factor,
        full_solve,
        full_residual: report.final_residual(),
        full_rounding_floor: report.rounding_floor,
        paper: paper.map(|p| p.1),
    })
}

/// `ours (paper, ×paper/ours)` for one cell.
fn cell(ours: f64, paper: Option<f64>) -> String {
    match paper {
        Some(p) => format!(
            "{} ({}, {})",
            seconds(ours),
            seconds(p),
            ratio(Some(p), Some(ours))
        ),
        None => seconds(ours),
    }
}

/// Table 1 as Markdown: every timing as `ours (paper, ×paper/ours)`; a second table with the
/// extra measurements (map time, residuals, repetitions).
pub fn markdown(rows: &[Table1Row]) -> String {
    let mut table = Table::new([
        "mesh",
        "#V / #F (paper #F)",
        "bases setup",
        "spline setup",
        "spline solve",
        "reduced soft factor",
        "reduced soft solve",
        "full soft factor",
        "full soft solve",
    ]);
    for r in rows {
        let p = r.paper;
        table.row([
            r.mesh.clone(),
            format!(
                "{} / {} ({})",
                thousands(r.vertices),
                thousands(r.faces),
                r.paper_faces.map_or("–".to_string(), thousands)
            ),
            cell(r.bases, p.map(|p| p.bases)),
            cell(r.spline_setup.median, p.map(|p| p.spline.0)),
            cell(r.spline_solve.median, p.map(|p| p.spline.1)),
            cell(r.reduced_factor.median, p.map(|p| p.reduced.0)),
            cell(r.reduced_solve.median, p.map(|p| p.reduced.1)),
            cell(r.full_factor.median, p.map(|p| p.full.0)),
            cell(r.full_solve.median, p.map(|p| p.full.1)),
        ]);
    }
    let mut extra = Table::new([
        "mesh",
        "basis fields",
        "constraints",
        "map x = U v",
        "spline max relative constraint residual",
        "full solve relative residual (rounding floor)",
        "runs (fast / full factor)",
    ]);
    for r in rows {
        extra.row([
            r.mesh.clone(),
            r.basis_fields.to_string(),
            r.constraints.to_string(),
            seconds(r.map.median),
            format!("{:.1e}", r.spline_residual),
            format!("{:.1e} ({:.1e})", r.full_residual, r.full_rounding_floor),
            format!("{} / {}", r.spline_setup.runs, r.full_factor.runs),
        ]);
    }
    format!(
        "{}\nEach cell: ours (paper, paper / ours). Medians of the runs in the second table; the \
         basis is one run.\n\n{}",
        table.to_markdown(),
        extra.to_markdown()
    )
}
