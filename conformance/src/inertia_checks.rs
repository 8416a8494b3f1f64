//! The eigenvalue core checks at real-mesh sizes (above [`crate::corpus::DENSE_LIMIT`]), through
//! the sparse eigensolver (`tvf_solvers::lowest_eigenpairs`) and inertia counts (the negative
//! pivots of a sparse `LDLᵀ` of `A − σ M` count the eigenvalues of `(A, M)` below `σ`, Sylvester's
//! law of inertia). What each measures, at any size:
//!
//! - `kernel dimension`: the eigenvalues of `L` (the pencil `(S, M1)` on the free field nodes)
//!   below `σ₀`, half the lowest nonzero eigenvalue of the two scalar pencils — one inertia
//!   count — equal the mesh's harmonic dimension.
//! - `spectrum union`: at [`UNION_SHIFTS`] shifts `σ` between consecutive distinct eigenvalues of
//!   the merged lowest [`SCALAR_PAIRS`] of each scalar pencil, the count of `L` below `σ` equals
//!   the harmonic dimension plus the nonzero eigenvalues of both scalar pencils below `σ` (each
//!   itself an inertia count): the low spectrum of `L` is the union of the scalar spectra, as a
//!   counting function at those shifts. The measured value is the largest count difference.
//! - `Lemma 1: unit eigenfields` and `Lemma 1: eigenfields of L`: the fields
//!   `d0 φ/√λ` and `−M1⁻¹ d1ᵀ ψ/√λ` of the lowest [`SCALAR_PAIRS`] nonzero scalar eigenpairs have
//!   unit `M1` norm (to 1e-9) and `‖L u − λ u‖_{M1} ≤ 1e-9 · λ_max` (`λ_max` a Gershgorin bound
//!   of `L`), the dense check's criteria on the low end of the spectrum.
//!
//! These need `S` as a sparse matrix, that is diagonal masses (a sparse mass puts its inverse,
//! a dense matrix, into `S` or into a scalar pencil): complexes with Galerkin masses keep the
//! dense checks' limit and report these checks as skipped with that reason.

use crate::check_outcome::CheckOutcome;
use crate::check_report::{DENSE_CHECK_NAMES, LEMMA1_CHECK_NAMES};
use sprs::CsMat;
use tvf_core::discretization::sparse::{mul_vec, restricted_to, transpose};
use tvf_core::discretization::{HodgeComplex, HodgeOperators, NodeSpace};
use tvf_solvers::convert::shifted_upper_triangle;
use tvf_solvers::{lowest_eigenpairs, EigenOptions, SparseLdlt};

/// Nonzero eigenpairs of each scalar pencil computed for the union and Lemma 1 checks.
pub const SCALAR_PAIRS: usize = 12;

/// Shifts at which the counts of the union check are compared.
pub const UNION_SHIFTS: usize = 4;

/// A pencil `(A, diag(m))` restricted to the free nodes of a space.
struct FreePencil {
    stiffness: CsMat<f64>,
    mass: Vec<f64>,
    free: Vec<usize>,
    /// Nodes of the space, free and fixed.
    len: usize,
    kernel: usize,
}

impl FreePencil {
    /// `(a, mass)` on the free nodes of `nodes`.
    fn new(a: &CsMat<f64>, mass: &[f64], nodes: &NodeSpace) -> Self {
        let free: Vec<usize> = (0..nodes.len()).filter(|&i| nodes.is_free(i)).collect();
        Self {
            stiffness: restricted(a, &free),
            mass: free.iter().map(|&i| mass[i]).collect(),
            free,
            len: nodes.len(),
            kernel: nodes.kernel_dimension(),
        }
    }

    /// A Gershgorin bound of the largest eigenvalue: `max_i Σ_j |A_ij| / m_i`.
    fn spectrum_bound(&self) -> f64 {
        let csr = self.stiffness.to_csr();
        (0..csr.rows())
            .map(|i| {
                let row: f64 = csr
                    .outer_view(i)
                    .map_or(0.0, |r| r.iter().map(|(_, v)| v.abs()).sum());
                row / self.mass[i]
            })
            .fold(0.0, f64::max)
    }

    /// The eigenvalues below `shift`, by the inertia of `A − shift · M`.
    fn count_below(&self, shift: f64) -> Result<usize, String> {
        let shifted = shifted_upper_triangle(&self.stiffness, &self.mass, shift)
            .map_err(|e| e.to_string())?;
        let factor = SparseLdlt::new(shifted.as_ref()).map_err(|e| e.to_string())?;
        Ok(factor.inertia().negative)
    }

    /// The lowest `count` nonzero eigenpairs (after the kernel), vectors on every node (zero on
    /// the fixed ones).
    fn lowest_nonzero(&self, count: usize) -> Result<Vec<(f64, Vec<f64>)>, String> {
        let k = (self.kernel + count).min(self.free.len());
        let pairs = lowest_eigenpairs(&self.stiffness, &self.mass, k, &EigenOptions::default())
            .map_err(|e| e.to_string())?;
        let full = |j: usize| {
            let mut x = vec![0.0; self.len];
            for (r, &i) in self.free.iter().enumerate() {
                x[i] = pairs.vectors[(r, j)];
            }
            x
        };
        Ok((self.kernel..pairs.values.len())
            .map(|j| (pairs.values[j], full(j)))
            .collect())
    }
}

/// `a` restricted to the rows and columns `keep`.
fn restricted(a: &CsMat<f64>, keep: &[usize]) -> CsMat<f64> {
    let mut position = vec![usize::MAX; a.rows().max(a.cols())];
    for (r, &i) in keep.iter().enumerate() {
        position[i] = r;
    }
    restricted_to(a, &position, &position, (keep.len(), keep.len()))
}

/// The outcomes of the eigenvalue checks under their names, all failed with `reason`.
fn all_failed(reason: &str) -> Vec<CheckOutcome> {
    DENSE_CHECK_NAMES
        .iter()
        .chain(&LEMMA1_CHECK_NAMES)
        .map(|name| CheckOutcome::failed(*name, reason.to_string()))
        .collect()
}

/// Why the checks cannot run on `complex`: a mass that is not diagonal.
pub fn unsupported_reason(complex: &dyn HodgeComplex) -> Option<String> {
    let sparse: Vec<&str> = [
        ("M0", complex.m0()),
        ("M1", complex.m1()),
        ("M2", complex.m2()),
    ]
    .into_iter()
    .filter(|(_, m)| !m.is_diagonal())
    .map(|(name, _)| name)
    .collect();
    (!sparse.is_empty()).then(|| {
        format!(
            "{} not diagonal: L's stiffness holds a dense inverse mass, so the sparse inertia \
             checks cannot factor it",
            sparse.join(", ")
        )
    })
}

/// The checks of the module documentation on `complex`, whose mesh has `harmonic_dimension`
/// harmonic fields (diagonal masses: see [`unsupported_reason`]).
pub fn measure_inertia_checks(
    complex: &dyn HodgeComplex,
    harmonic_dimension: usize,
) -> Vec<CheckOutcome> {
    let run = || -> Result<Vec<CheckOutcome>, String> {
        let diagonal = |m: &tvf_core::discretization::Mass| {
            m.diagonal_values()
                .map(<[f64]>::to_vec)
                .ok_or("a mass is not diagonal")
        };
        let (m0, m1) = (diagonal(complex.m0())?, diagonal(complex.m1())?);
        let m2_inverse = complex
            .m2()
            .inverse_diagonal()
            .ok_or("M2 is not diagonal")?;
        let laplacian = complex
            .dirichlet_energy()
            .as_sparse()
            .ok_or("S is not a sparse matrix")?
            .clone();
        let co_stiffness = complex
            .co_potential_stiffness()
            .as_sparse()
            .ok_or("the co-potential stiffness is not a sparse matrix")?
            .clone();
        let field = FreePencil::new(&laplacian, &m1, complex.field_nodes());
        let potential = FreePencil::new(
            complex.potential_stiffness(),
            &m0,
            complex.potential_nodes(),
        );
        let co_potential =
            FreePencil::new(&co_stiffness, &m2_inverse, complex.co_potential_nodes());
        let integrable = potential.lowest_nonzero(SCALAR_PAIRS)?;
        let cointegrable = co_potential.lowest_nonzero(SCALAR_PAIRS)?;
        let mut merged: Vec<f64> = integrable
            .iter()
            .chain(&cointegrable)
            .map(|p| p.0)
            .collect();
        merged.sort_by(f64::total_cmp);
        let lowest = merged
            .first()
            .copied()
            .ok_or("no nonzero scalar eigenvalue")?;
        let mut outcomes = semidefinite_outcomes([&field, &potential, &co_potential])?;
        outcomes.extend(zero_outcomes(
            [&field, &potential, &co_potential],
            lowest / 2.0,
            harmonic_dimension,
        )?);
        outcomes.push(union_outcome(
            [&field, &potential, &co_potential],
            &merged,
            harmonic_dimension,
        )?);
        outcomes.extend(lemma1_outcomes(
            complex,
            &laplacian,
            &m1,
            &integrable,
            &cointegrable,
        ));
        Ok(outcomes)
    };
    run().unwrap_or_else(|reason| all_failed(&format!("the sparse checks failed: {reason}")))
}

/// `positive semi-definite: …` of `S` and both scalar pencils: no eigenvalue below
/// `−1e-10 · λ_max` (the dense check's tolerance; `λ_max` a Gershgorin bound), by inertia; `B`
/// (`S M1⁻¹ S`) is semi-definite whenever `S` is symmetric and is not factored (skipped).
fn semidefinite_outcomes(pencils: [&FreePencil; 3]) -> Result<Vec<CheckOutcome>, String> {
    let names = ["S", "exact eigenproblem", "co-exact eigenproblem"];
    let mut outcomes = Vec::new();
    for (pencil, what) in pencils.into_iter().zip(names) {
        let shift = -1e-10 * pencil.spectrum_bound();
        let negative = pencil.count_below(shift)?;
        outcomes.push(CheckOutcome::count(
            format!("positive semi-definite: {what}"),
            negative,
            0,
            format!("{what}: {negative} eigenvalues below σ = {shift:.3e} (inertia of A − σ M)"),
        ));
    }
    outcomes.insert(
        1,
        CheckOutcome::skipped(
            "positive semi-definite: B",
            "B = S M1⁻¹ S is semi-definite when S is symmetric; not factored at this size"
                .to_string(),
        ),
    );
    Ok(outcomes)
}

/// `kernel dimension` and `zeros of L` (eigenvalues of `L` below `shift`), `zeros of the exact
/// pair` and `zeros of the co-exact pair` (each scalar pencil's below `shift`, against the
/// kernel dimension of its space).
fn zero_outcomes(
    [field, potential, co_potential]: [&FreePencil; 3],
    shift: f64,
    harmonic_dimension: usize,
) -> Result<Vec<CheckOutcome>, String> {
    let below = field.count_below(shift)?;
    let detail = format!(
        "dim ker L = {below} by the inertia of S − σ M1 at σ = {shift:.3e} (half the lowest \
         nonzero scalar eigenvalue; {} free field nodes), expected {harmonic_dimension}",
        field.free.len()
    );
    let mut outcomes = vec![
        CheckOutcome::count(
            "kernel dimension",
            below,
            harmonic_dimension,
            detail.clone(),
        ),
        CheckOutcome::count("zeros of L", below, harmonic_dimension, detail),
    ];
    for (pencil, which) in [(potential, "exact"), (co_potential, "co-exact")] {
        let zeros = pencil.count_below(shift)?;
        outcomes.push(CheckOutcome::count(
            format!("zeros of the {which} pair"),
            zeros,
            pencil.kernel,
            format!(
                "the {which} pair has {zeros} eigenvalues below σ = {shift:.3e}, expected {}",
                pencil.kernel
            ),
        ));
    }
    Ok(outcomes)
}

/// `spectrum union`: the count differences at shifts between consecutive distinct eigenvalues
/// of `merged` (ascending), up to where both scalar pencils' computed pairs reach.
fn union_outcome(
    [field, potential, co_potential]: [&FreePencil; 3],
    merged: &[f64],
    harmonic_dimension: usize,
) -> Result<CheckOutcome, String> {
    // Shifts below the SCALAR_PAIRS-th merged eigenvalue, where no pair is missing.
    let reach = merged.len().min(SCALAR_PAIRS);
    let gaps: Vec<f64> = (1..reach)
        .filter(|&i| merged[i] > merged[i - 1] * (1.0 + 1e-6))
        .map(|i| (merged[i - 1] * merged[i]).sqrt())
        .collect();
    let step = (gaps.len() / UNION_SHIFTS).max(1);
    let shifts: Vec<f64> = gaps
        .iter()
        .copied()
        .step_by(step)
        .take(UNION_SHIFTS)
        .collect();
    let mut worst = 0usize;
    let mut detail = Vec::new();
    for &shift in &shifts {
        let l = field.count_below(shift)?;
        let integrable = potential
            .count_below(shift)?
            .saturating_sub(potential.kernel);
        let cointegrable = co_potential
            .count_below(shift)?
            .saturating_sub(co_potential.kernel);
        let expected = harmonic_dimension + integrable + cointegrable;
        worst = worst.max(l.abs_diff(expected));
        detail.push(format!(
            "σ = {shift:.3e}: L {l}, {harmonic_dimension} + {integrable} + {cointegrable}"
        ));
    }
    Ok(CheckOutcome::count(
        "spectrum union",
        worst,
        0,
        format!(
            "eigenvalues below σ, by inertia counts, of L against harmonic + integrable + \
             co-integrable: {}",
            detail.join("; ")
        ),
    ))
}

/// Lemma 1 on the computed scalar eigenpairs: unit norms and residuals of their eigenfields.
fn lemma1_outcomes(
    complex: &dyn HodgeComplex,
    laplacian: &CsMat<f64>,
    m1: &[f64],
    integrable: &[(f64, Vec<f64>)],
    cointegrable: &[(f64, Vec<f64>)],
) -> Vec<CheckOutcome> {
    let lambda_max = (0..laplacian.rows())
        .map(|i| {
            let row = laplacian
                .outer_view(i)
                .map_or(0.0, |r| r.iter().map(|(_, v)| v.abs()).sum());
            if m1[i] > 0.0 {
                row / m1[i]
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max);
    let norm = |u: &[f64]| u.iter().zip(m1).map(|(x, m)| x * x * m).sum::<f64>().sqrt();
    let d1t = transpose(complex.d1());
    let fields = integrable
        .iter()
        .map(|(l, phi)| (*l, mul_vec(complex.d0(), phi)))
        .chain(cointegrable.iter().map(|(l, psi)| {
            let u: Vec<f64> = mul_vec(&d1t, psi)
                .iter()
                .zip(m1)
                .map(|(x, m)| -x / m)
                .collect();
            (*l, u)
        }));
    let (mut worst_norm, mut worst_residual) = (0.0f64, 0.0f64);
    let mut count = 0;
    for (lambda, gradient) in fields {
        let u: Vec<f64> = gradient.iter().map(|x| x / lambda.sqrt()).collect();
        worst_norm = worst_norm.max((norm(&u) - 1.0).abs());
        let su = mul_vec(laplacian, &u);
        let residual: Vec<f64> = su
            .iter()
            .zip(&u)
            .zip(m1)
            .map(|((s, x), m)| if *m > 0.0 { s / m - lambda * x } else { 0.0 })
            .collect();
        worst_residual = worst_residual.max(norm(&residual));
        count += 1;
    }
    vec![
        CheckOutcome::at_most(
            "Lemma 1: unit eigenfields",
            worst_norm,
            1e-9,
            format!(
                "{count} eigenfields of the lowest scalar pairs: M1 norm off by {worst_norm:e}"
            ),
        ),
        CheckOutcome::at_most(
            "Lemma 1: eigenfields of L",
            worst_residual,
            1e-9 * lambda_max,
            format!(
                "{count} eigenfields: |L u − λ u| = {worst_residual:e} (λ_max ≤ {lambda_max:e}, \
                 Gershgorin)"
            ),
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check_report::core_check_report;
    use crate::corpus::staggered_torus;
    use tvf_discretizations::catalog_entry;

    /// Above the dense limit every eigenvalue check runs (none skipped for size) and passes on
    /// a correct complex; told the wrong harmonic dimension, the kernel and the union fail with
    /// their counts.
    #[test]
    fn large_complexes_get_every_check_by_inertia() {
        let mesh = staggered_torus(1.0, 0.4, 40, 16);
        for id in [
            "conforming-barycentric",
            "dec-circumcentric",
            "nonconforming-voronoi",
        ] {
            let built = catalog_entry(id).unwrap().build(&mesh).unwrap();
            assert!(built.field_dimension() > crate::corpus::DENSE_LIMIT);
            let report = core_check_report(built.as_ref(), &mesh);
            assert!(report.passed(), "{id}: {:?}", report.failure_lines());
            let skipped: Vec<&str> = report
                .outcomes
                .iter()
                .filter(|o| o.status == crate::check_outcome::CheckStatus::Skipped)
                .map(|o| o.name.as_str())
                .collect();
            assert_eq!(skipped, ["positive semi-definite: B"], "{id}");
            let wrong = measure_inertia_checks(built.as_ref(), 0);
            let failed: Vec<(&str, f64)> = wrong
                .iter()
                .filter(|o| o.failed_check())
                .map(|o| (o.name.as_str(), o.measured))
                .collect();
            assert!(
                failed.contains(&("kernel dimension", 2.0))
                    && failed
                        .iter()
                        .any(|(n, m)| *n == "spectrum union" && *m == 2.0),
                "{id}: {failed:?}"
            );
        }
    }

    /// A complex with a Galerkin mass above the dense limit: the checks say why they are skipped.
    #[test]
    fn sparse_masses_are_named_as_the_reason() {
        let mesh = staggered_torus(1.0, 0.4, 40, 16);
        let built = catalog_entry("whitney-galerkin")
            .unwrap()
            .build(&mesh)
            .unwrap();
        let reason = unsupported_reason(built.as_ref()).unwrap();
        assert!(reason.contains("M0, M1 not diagonal"), "{reason}");
    }
}
