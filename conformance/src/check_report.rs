//! [`core_check_report`]: the core checks of the suite run on one complex and one mesh, returned
//! as a report instead of asserted — the same measurements the suite asserts on
//! ([`crate::check_outcome`]), for complexes built outside this crate (the Python package's
//! `tvf.check` on a researcher's own matrices).

use crate::algebra_checks::{
    measure_d1_d0_zero, measure_masses, measure_psd_operators_with,
    measure_symmetric_operators_with,
};
use crate::check_cache::CheckCache;
use crate::check_outcome::CheckOutcome;
use crate::corpus::{DENSE_LIMIT, EIGENVECTOR_LIMIT};
use crate::decomposition_checks::{
    measure_hodge_decomposition_with, measure_kernel_dimension_dense_with,
};
use crate::inertia_checks::{measure_inertia_checks, unsupported_reason};
use crate::spectral_checks::{measure_lemma1_with, measure_spectrum_union_with};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::mesh::Mesh;
use tvf_discretizations::mesh_topology;

/// Seed of the random fields of the decomposition checks.
const SEED: u64 = 17;

/// The names of the outcomes of the dense eigenvalue checks (semi-definiteness, the kernel, the
/// spectrum union), as measured and as skipped above [`DENSE_LIMIT`]: one name per check, so
/// that a run over meshes of both sizes reports each check once.
pub const DENSE_CHECK_NAMES: [&str; 9] = [
    "positive semi-definite: S",
    "positive semi-definite: B",
    "positive semi-definite: exact eigenproblem",
    "positive semi-definite: co-exact eigenproblem",
    "kernel dimension",
    "zeros of L",
    "zeros of the exact pair",
    "zeros of the co-exact pair",
    "spectrum union",
];

/// The names of the outcomes of the Lemma 1 check, as measured and as skipped above
/// [`EIGENVECTOR_LIMIT`].
pub const LEMMA1_CHECK_NAMES: [&str; 2] =
    ["Lemma 1: unit eigenfields", "Lemma 1: eigenfields of L"];

/// Every outcome of [`core_check_report`], in a fixed order.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckReport {
    /// The outcomes, one per measured property.
    pub outcomes: Vec<CheckOutcome>,
}

impl CheckReport {
    /// Whether no check failed (skipped ones do not count).
    pub fn passed(&self) -> bool {
        !self.outcomes.iter().any(CheckOutcome::failed_check)
    }

    /// The failed outcomes.
    pub fn failures(&self) -> Vec<&CheckOutcome> {
        self.outcomes.iter().filter(|o| o.failed_check()).collect()
    }

    /// One line per failed outcome: `name = measured (limit limit): detail`.
    pub fn failure_lines(&self) -> Vec<String> {
        self.failures()
            .iter()
            .map(|o| {
                format!(
                    "{} = {:e} (limit {:e}): {}",
                    o.name, o.measured, o.limit, o.detail
                )
            })
            .collect()
    }
}

/// Runs the core checks on `complex` built on `mesh`: `d1 d0 = 0` and integrable ⟂
/// co-integrable; masses positive (a diagonal on the used nodes, a sparse matrix definite on the
/// free nodes) with `1ᵀ M0 1 = area`; `S`, `B` and both stiffness matrices symmetric; the Hodge
/// decomposition; and, when `n1 ≤` [`DENSE_LIMIT`], positive
/// semi-definiteness, `dim ker L` (the mesh's harmonic dimension) and the spectrum of `L` as the
/// union of the two scalar spectra, and Lemma 1's eigenfields, densely when
/// `n1 ≤` [`EIGENVECTOR_LIMIT`]; above it, for complexes with diagonal masses, the same checks by
/// the sparse eigensolver and inertia counts ([`crate::inertia_checks`]); a complex with a sparse
/// mass keeps the dense checks up to [`DENSE_LIMIT`] (Lemma 1 up to [`EIGENVECTOR_LIMIT`]) and
/// gets the others reported as skipped, saying why. The spectra, eigenfields and the decomposer
/// these checks share are computed once ([`CheckCache`]).
pub fn core_check_report<M: Mesh + ?Sized>(complex: &dyn HodgeComplex, mesh: &M) -> CheckReport {
    let cache = CheckCache::new(complex);
    let harmonic_dimension =
        mesh_topology(mesh, complex.topology().boundary_condition).harmonic_dimension;
    let n1 = complex.field_dimension();
    let mut outcomes = measure_d1_d0_zero(complex);
    outcomes.extend(measure_masses(complex, mesh));
    outcomes.push(CheckOutcome::count(
        "reported harmonic dimension",
        complex.topology().harmonic_dimension,
        harmonic_dimension,
        format!(
            "the complex reports {}, the mesh's topology gives {harmonic_dimension}",
            complex.topology().harmonic_dimension
        ),
    ));
    outcomes.extend(measure_symmetric_operators_with(&cache));
    outcomes.extend(measure_hodge_decomposition_with(&cache, SEED));
    let too_large = |limit: usize| format!("n1 = {n1} is above the dense limit {limit}");
    let sparse_reason = unsupported_reason(complex);
    if n1 <= EIGENVECTOR_LIMIT || (n1 <= DENSE_LIMIT && sparse_reason.is_some()) {
        outcomes.extend(measure_psd_operators_with(&cache));
        outcomes.push(measure_kernel_dimension_dense_with(
            &cache,
            harmonic_dimension,
        ));
        outcomes.extend(measure_spectrum_union_with(&cache, harmonic_dimension));
        if n1 <= EIGENVECTOR_LIMIT {
            outcomes.extend(measure_lemma1_with(&cache));
        } else {
            let reason = sparse_reason.unwrap_or_default();
            outcomes.extend(LEMMA1_CHECK_NAMES.iter().map(|name| {
                CheckOutcome::skipped(*name, format!("{}; {reason}", too_large(EIGENVECTOR_LIMIT)))
            }));
        }
    } else {
        match sparse_reason {
            // Real-mesh sizes: the sparse eigensolver and inertia counts.
            None => outcomes.extend(measure_inertia_checks(complex, harmonic_dimension)),
            Some(reason) => outcomes.extend(
                DENSE_CHECK_NAMES
                    .iter()
                    .chain(&LEMMA1_CHECK_NAMES)
                    .map(|name| {
                        CheckOutcome::skipped(
                            *name,
                            format!("{}; {reason}", too_large(DENSE_LIMIT)),
                        )
                    }),
            ),
        }
    }
    CheckReport { outcomes }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sprs::CsMat;
    use tvf_core::discretization::Mass;
    use tvf_core::generate::torus;
    use tvf_discretizations::{catalog_entry, MatrixComplex, MatrixSampling};

    #[test]
    fn a_catalog_complex_passes_and_a_broken_mass_is_named() {
        let mesh = torus(1.0, 0.4, 10, 6).unwrap();
        let built = catalog_entry("nonconforming-voronoi")
            .unwrap()
            .build(&mesh)
            .unwrap();
        let report = core_check_report(built.as_ref(), &mesh);
        assert!(report.passed(), "{:?}", report.failures());
        assert!(report.outcomes.len() >= 20);
        // The measured names are the ones a check skipped for size is reported under.
        for name in DENSE_CHECK_NAMES.iter().chain(&LEMMA1_CHECK_NAMES) {
            assert!(
                report.outcomes.iter().any(|o| o.name == *name),
                "no outcome named {name}"
            );
        }
        let mut m0 = built.m0().diagonal_values().unwrap().to_vec();
        m0[3] *= 1.5; // 1ᵀ M0 1 no longer the area
        let d0: CsMat<f64> = built.d0().clone();
        let broken = MatrixComplex::new(
            "broken",
            &mesh.clone().into(),
            d0,
            built.d1().clone(),
            Mass::diagonal("M0", m0).unwrap(),
            built.m1().clone(),
            built.m2().clone(),
            MatrixSampling::None,
        )
        .unwrap();
        let report = core_check_report(&broken, &mesh);
        let failed: Vec<&str> = report.failures().iter().map(|o| o.name.as_str()).collect();
        assert!(
            failed.contains(&"potential_masses_sum_to_area"),
            "{failed:?}"
        );
    }
}
