//! [`core_check_report`]: the core checks of the suite run on one complex and one mesh, returned
//! as a report instead of asserted — the same measurements the suite asserts on
//! ([`crate::check_outcome`]), for complexes built outside this crate (the Python package's
//! `tvf.check` on a researcher's own matrices).

use crate::algebra_checks::{
    measure_d1_d0_zero, measure_masses, measure_psd_operators, measure_symmetric_operators,
};
use crate::check_outcome::CheckOutcome;
use crate::corpus::{DENSE_LIMIT, EIGENVECTOR_LIMIT};
use crate::decomposition_checks::{measure_hodge_decomposition, measure_kernel_dimension_dense};
use crate::spectral_checks::{measure_lemma1, measure_spectrum_union};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::TriangleMesh;
use tvf_discretizations::mesh_topology;

/// Seed of the random fields of the decomposition checks.
const SEED: u64 = 17;

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
}

/// Runs the core checks on `complex` built on `mesh`: `d1 d0 = 0` and integrable ⟂
/// co-integrable; masses positive (a diagonal on the used nodes, a sparse matrix definite on the
/// free nodes) with `1ᵀ M0 1 = area`; `S`, `B` and both stiffness matrices symmetric; the Hodge
/// decomposition; and, when `n1 ≤` [`DENSE_LIMIT`], positive
/// semi-definiteness, `dim ker L` (the mesh's harmonic dimension) and the spectrum of `L` as the
/// union of the two scalar spectra, when `n1 ≤` [`EIGENVECTOR_LIMIT`] Lemma 1's eigenfields
/// (larger complexes get these reported as skipped).
pub fn core_check_report(complex: &dyn HodgeComplex, mesh: &TriangleMesh) -> CheckReport {
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
    outcomes.extend(measure_symmetric_operators(complex));
    outcomes.extend(measure_hodge_decomposition(complex, SEED));
    let too_large = |limit: usize| format!("n1 = {n1} is above the dense limit {limit}");
    if n1 <= DENSE_LIMIT {
        outcomes.extend(measure_psd_operators(complex));
        outcomes.push(measure_kernel_dimension_dense(complex, harmonic_dimension));
        outcomes.extend(measure_spectrum_union(complex, harmonic_dimension));
    } else {
        for name in [
            "positive semi-definite operators",
            "kernel dimension",
            "spectrum union",
        ] {
            outcomes.push(CheckOutcome::skipped(name, too_large(DENSE_LIMIT)));
        }
    }
    if n1 <= EIGENVECTOR_LIMIT {
        outcomes.extend(measure_lemma1(complex));
    } else {
        outcomes.push(CheckOutcome::skipped(
            "Lemma 1",
            too_large(EIGENVECTOR_LIMIT),
        ));
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
