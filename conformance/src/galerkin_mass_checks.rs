//! The reference check `galerkin_masses`: every mass of a complex is the Galerkin (`L²`) mass of
//! the functions it evaluates or samples, assembled here from the capabilities alone.

use crate::check_outcome::{assert_outcomes, CheckOutcome};
use crate::corpus::CorpusMesh;
use crate::reference_formulas::matrix_deviation;
use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{FieldSampling, HodgeComplex};
use tvf_core::geometry::dot;
use tvf_core::{SurfacePoint, TriangleMesh};

/// The edge midpoints of a triangle in barycentric coordinates: `∫_T g = |T|/3 Σ g(m)` holds
/// exactly for polynomials `g` of degree at most 2, so for the product of two linear functions.
const EDGE_MIDPOINTS: [[f64; 3]; 3] = [[0.0, 0.5, 0.5], [0.5, 0.0, 0.5], [0.5, 0.5, 0.0]];

/// Largest deviation allowed, relative to the largest entry: the two assemblies differ only in
/// the order of their sums.
const TOLERANCE: f64 = 1e-12;

/// `G[i, j] = Σ_T ∫_T ψ_i ψ_j` (`n × n`, area) for the scalar functions whose values at a point
/// of a face are `weights(face, barycentric)` (`(node, value)` pairs), each linear (or constant)
/// on every face.
pub fn evaluated_mass(
    mesh: &TriangleMesh,
    n: usize,
    weights: impl Fn(usize, [f64; 3]) -> Vec<(usize, f64)>,
) -> CsMat<f64> {
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for t in 0..mesh.face_count() {
        let area = mesh.face_area(t);
        for b in EDGE_MIDPOINTS {
            let w = weights(t, b);
            for &(i, a) in &w {
                for &(j, c) in &w {
                    rows.push(i);
                    cols.push(j);
                    values.push(area / 3.0 * a * c);
                }
            }
        }
    }
    from_triplets(n, n, rows, cols, values)
}

/// `G[e, f] = Σ_T ∫_T ⟨w_e, w_f⟩` (`n1 × n1`) for the fields `w_e` the sampling gives each field
/// node (its sampling weights), each linear (or constant) on every face.
pub fn sampled_mass(mesh: &TriangleMesh, sampling: &dyn FieldSampling) -> CsMat<f64> {
    let n = sampling.field_dimension();
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for t in 0..mesh.face_count() {
        let area = mesh.face_area(t);
        for b in EDGE_MIDPOINTS {
            let w = sampling.sample_weights(&SurfacePoint::barycentric(t, b));
            for &(i, u) in &w {
                for &(j, v) in &w {
                    rows.push(i);
                    cols.push(j);
                    values.push(area / 3.0 * dot(u, v));
                }
            }
        }
    }
    from_triplets(n, n, rows, cols, values)
}

/// Reference `galerkin_masses`: `M0 = ∫ ψ_i ψ_j` of the potentials' point evaluation,
/// `M1 = ∫ ⟨w_e, w_f⟩` of the sampled fields and `M2⁻¹ = ∫ χ_i χ_j` of the co-potentials' point
/// evaluation, each within `1e-12 · max |entry|` (exact quadrature; the masses as stored, `M2⁻¹`
/// through [`tvf_core::discretization::Mass::inverse`]). Lumped masses fail it; consistent ones
/// pass. Needs sampling and point evaluation; fields must be sampled linearly in each face
/// (face vectors, Whitney forms) and fixed field nodes have no weight, so a closed mesh.
pub fn check_galerkin_masses<H: HodgeComplex + ?Sized>(complex: &H, mesh: &CorpusMesh) {
    assert_outcomes(&measure_galerkin_masses(complex, &mesh.mesh));
}

/// [`check_galerkin_masses`] measured: one outcome per mass (`galerkin_masses:M0`, `:M1`,
/// `:M2_inverse`), the largest deviation relative to the largest assembled entry against
/// `1e-12`; a complex without sampling or point evaluation, or with a mass stored as its
/// inverse, fails naming what is missing.
pub fn measure_galerkin_masses<H: HodgeComplex + ?Sized>(
    complex: &H,
    mesh: &TriangleMesh,
) -> Vec<CheckOutcome> {
    const NAME: &str = "galerkin_masses";
    let (Some(evaluation), Some(sampling)) = (complex.point_evaluation(), complex.sampling())
    else {
        return vec![CheckOutcome::failed(
            NAME,
            "needs point evaluation and sampling".to_string(),
        )];
    };
    let stored = (
        complex.m0().sparse_matrix(),
        complex.m1().sparse_matrix(),
        complex.m2().inverse().sparse_matrix(),
    );
    let (Some(m0), Some(m1), Some(co_mass)) = stored else {
        return vec![CheckOutcome::failed(
            NAME,
            "M0 and M1 must be stored directly and M2⁻¹ must be sparse".to_string(),
        )];
    };
    let potentials = evaluated_mass(mesh, m0.rows(), |t, b| {
        evaluation.potential_weights(&SurfacePoint::barycentric(t, b))
    });
    let co_potentials = evaluated_mass(mesh, co_mass.rows(), |t, b| {
        evaluation.co_potential_weights(&SurfacePoint::barycentric(t, b))
    });
    let fields = sampled_mass(mesh, sampling);
    [
        ("M0", "M0 vs ∫ψψ of the potentials", &m0, &potentials),
        ("M1", "M1 vs ∫⟨w, w⟩ of the sampled fields", &m1, &fields),
        (
            "M2_inverse",
            "M2⁻¹ vs ∫χχ of the co-potentials",
            &co_mass,
            &co_potentials,
        ),
    ]
    .into_iter()
    .map(|(mass, what, stored, assembled)| {
        let name = format!("{NAME}:{mass}");
        match matrix_deviation(stored, assembled) {
            Some((error, scale)) => CheckOutcome::at_most(
                name,
                if scale > 0.0 { error / scale } else { error },
                TOLERANCE,
                format!("{what}: differs by {error:e} (max entry {scale:e})"),
            ),
            None => CheckOutcome::failed(name, format!("{what}: shapes differ")),
        }
    })
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::discretization::{ComplexParts, PointEvaluation};
    use tvf_core::generate::icosphere;

    /// A complex's parts with the capabilities of another complex.
    struct Swapped<'a>(ComplexParts, &'a dyn HodgeComplex);

    impl HodgeComplex for Swapped<'_> {
        fn parts(&self) -> &ComplexParts {
            &self.0
        }

        fn sampling(&self) -> Option<&dyn FieldSampling> {
            self.1.sampling()
        }

        fn point_evaluation(&self) -> Option<&dyn PointEvaluation> {
            self.1.point_evaluation()
        }
    }

    #[test]
    #[should_panic(expected = "M0 vs ∫ψψ of the potentials")]
    fn a_lumped_potential_mass_is_not_the_galerkin_mass() {
        let mesh = CorpusMesh::new("icosphere(1)", icosphere(1), 0);
        let entry = tvf_discretizations::catalog_entry("conforming-barycentric").unwrap();
        check_galerkin_masses(entry.build(&mesh.mesh).unwrap().as_ref(), &mesh);
    }

    #[test]
    #[should_panic(expected = "M1 vs ∫⟨w, w⟩ of the sampled fields")]
    fn the_dec_star_is_not_the_whitney_mass() {
        let mesh = CorpusMesh::new("icosphere(1)", icosphere(1), 0);
        let entry = tvf_discretizations::catalog_entry("dec-barycentric").unwrap();
        let complex = entry.build(&mesh.mesh).unwrap();
        // DEC's M0 is lumped too; compare M1 alone by swapping in the Galerkin M0.
        let galerkin = tvf_discretizations::catalog_entry("whitney-galerkin").unwrap();
        let m0 = galerkin.build(&mesh.mesh).unwrap().m0().clone();
        let parts = ComplexParts::new(
            "dec-with-galerkin-m0",
            complex.d0().clone(),
            complex.d1().clone(),
            [m0, complex.m1().clone(), complex.m2().clone()],
            [
                complex.potential_nodes().clone(),
                complex.field_nodes().clone(),
                complex.co_potential_nodes().clone(),
            ],
            *complex.topology(),
        )
        .unwrap();
        check_galerkin_masses(&Swapped(parts, complex.as_ref()), &mesh);
    }
}
