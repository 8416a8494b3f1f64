//! [`BasisComparison`]: how two discretizations' Fourier bases of the same mesh agree — their
//! eigenvalues index by index, and how much of each eigenfield of one lies in the span of the
//! other's. Fields of different discretizations live in different coefficient spaces, so both
//! are compared as what they mean on the surface: one tangent vector per face, sampled at the
//! face's centroid, with the area-weighted inner product `⟨u, v⟩ = Σ_f |A_f| ⟨u_f, v_f⟩`.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use thiserror::Error;
use tvf_core::discretization::{DiscretizationError, HodgeComplex, HodgeOperators};
use tvf_core::SurfaceMesh;

use crate::basis::SpectralBasis;

/// Eigenvalues at most this fraction of the largest compared one count as zero (harmonic) on
/// both sides: their relative difference is reported as 0.
const ZERO_EIGENVALUE_RELATIVE: f64 = 1e-9;

/// Why two bases cannot be compared.
#[derive(Debug, Error)]
pub enum BasisComparisonError {
    /// A complex cannot sample its fields as vectors (fields of its basis have no meaning on the
    /// surface to compare).
    #[error(transparent)]
    Sampling(#[from] DiscretizationError),
    /// The sampled fields of a basis are linearly dependent (or a sampled field is zero), so
    /// the projection onto their span is not defined.
    #[error(
        "the sampled fields of '{id}' are linearly dependent in the area-weighted inner product \
         (their Gram matrix is not positive definite)"
    )]
    DependentFields {
        /// The complex's id.
        id: String,
    },
    /// A sampled value is not finite.
    #[error("a sampled field of '{id}' is not finite")]
    NotFinite {
        /// The complex's id.
        id: String,
    },
}

/// A basis as vectors on the surface: `3F × d`, column `j` the sampled field `j` (rows
/// `3f..3f+3` its vector at face `f`'s centroid), with its eigenvalues (`d`, ascending).
pub struct SampledBasis {
    /// What names the basis in comparisons: the complex's id unless the caller renames it.
    pub id: String,
    /// Eigenvalues, ascending, in 1/length².
    pub eigenvalues: Vec<f64>,
    /// The sampled fields, `3F × d`.
    pub vectors: Mat<f64>,
}

impl SampledBasis {
    /// Samples every field of `basis` (computed for `complex` on `mesh`) at the face centroids.
    pub fn new(
        complex: &dyn HodgeComplex,
        basis: &SpectralBasis,
    ) -> Result<Self, BasisComparisonError> {
        let sampling = complex.require_sampling()?;
        let faces = sampling.face_count();
        let fields = basis.fields();
        let mut vectors = Mat::<f64>::zeros(3 * faces, basis.len());
        for f in 0..faces {
            for (i, w) in sampling.sample_weights(&sampling.centroid(f)) {
                for j in 0..basis.len() {
                    let x = fields[(i, j)];
                    for (k, wk) in w.iter().enumerate() {
                        vectors[(3 * f + k, j)] += wk * x;
                    }
                }
            }
        }
        let finite = (0..vectors.ncols()).all(|j| vectors.col(j).iter().all(|x| x.is_finite()));
        if !finite {
            return Err(BasisComparisonError::NotFinite {
                id: complex.id().to_string(),
            });
        }
        Ok(Self {
            id: complex.id().to_string(),
            eigenvalues: basis.eigenvalues().to_vec(),
            vectors,
        })
    }
}

/// Two bases of one mesh compared over their first `d = min(d_a, d_b)` fields.
#[derive(Debug, Clone)]
pub struct BasisComparison {
    /// The first basis's complex id.
    pub first: String,
    /// The second basis's complex id.
    pub second: String,
    /// `|λ_a − λ_b| / max(λ_a, λ_b)` index by index (0 where both are zero), `d` entries.
    pub eigenvalue_differences: Vec<f64>,
    /// For each of the first basis's `d` fields, the fraction of its squared norm that lies in
    /// the span of the second's `d` fields (1: entirely, 0: orthogonal to all of them).
    pub first_in_second: Vec<f64>,
    /// The same with the roles exchanged.
    pub second_in_first: Vec<f64>,
}

impl BasisComparison {
    /// Compares `a` and `b`, sampled on `mesh`.
    pub fn new(
        mesh: &SurfaceMesh,
        a: &SampledBasis,
        b: &SampledBasis,
    ) -> Result<Self, BasisComparisonError> {
        let d = a.eigenvalues.len().min(b.eigenvalues.len());
        let weights: Vec<f64> = (0..mesh.face_count())
            .flat_map(|f| [mesh.face_area(f); 3])
            .collect();
        let weighted = |m: &Mat<f64>| Mat::from_fn(m.nrows(), d, |r, c| weights[r] * m[(r, c)]);
        let va = a.vectors.subcols(0, d).to_owned();
        let vb = b.vectors.subcols(0, d).to_owned();
        let (wa, wb) = (weighted(&va), weighted(&vb));
        let gram_a = va.transpose() * &wa;
        let gram_b = vb.transpose() * &wb;
        let cross = vb.transpose() * &wa; // d × d: ⟨b_i, a_j⟩
        let first_in_second = captured(&gram_b, &cross, &gram_a, &b.id)?;
        let second_in_first = captured(&gram_a, &cross.transpose().to_owned(), &gram_b, &a.id)?;
        let largest = a.eigenvalues[..d]
            .iter()
            .chain(&b.eigenvalues[..d])
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let eigenvalue_differences = (0..d)
            .map(|i| {
                let (x, y) = (a.eigenvalues[i], b.eigenvalues[i]);
                let scale = x.abs().max(y.abs());
                if scale <= ZERO_EIGENVALUE_RELATIVE * largest {
                    0.0
                } else {
                    (x - y).abs() / scale
                }
            })
            .collect();
        Ok(Self {
            first: a.id.clone(),
            second: b.id.clone(),
            eigenvalue_differences,
            first_in_second,
            second_in_first,
        })
    }
}

/// For each column `j`: `c_jᵀ G⁻¹ c_j / n_jj`, the fraction of field `j`'s squared norm
/// (`n_jj`, the diagonal of `norms`) in the span whose Gram matrix is `gram`, `cross` holding the
/// inner products of the span's fields (rows) with the fields (columns).
fn captured(
    gram: &Mat<f64>,
    cross: &Mat<f64>,
    norms: &Mat<f64>,
    span_id: &str,
) -> Result<Vec<f64>, BasisComparisonError> {
    let factor = gram
        .llt(Side::Lower)
        .map_err(|_| BasisComparisonError::DependentFields {
            id: span_id.to_string(),
        })?;
    let solved = factor.solve(cross);
    Ok((0..cross.ncols())
        .map(|j| {
            let projected: f64 = (0..cross.nrows())
                .map(|i| cross[(i, j)] * solved[(i, j)])
                .sum();
            projected / norms[(j, j)]
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{compute_basis, BasisRequest};
    use tvf_core::generate::icosphere;
    use tvf_discretizations::catalog_entry;

    fn sampled(id: &str, mesh: &SurfaceMesh, d: usize) -> SampledBasis {
        let complex = catalog_entry(id).unwrap().build(mesh).unwrap();
        let basis = compute_basis(complex.as_ref(), &BasisRequest::fields(d)).unwrap();
        SampledBasis::new(complex.as_ref(), &basis).unwrap()
    }

    #[test]
    fn a_basis_agrees_with_itself_and_two_discretizations_nearly_agree_on_a_sphere() {
        let mesh = SurfaceMesh::from(icosphere(3));
        let conforming = sampled("conforming-barycentric", &mesh, 16);
        let same = BasisComparison::new(&mesh, &conforming, &conforming).unwrap();
        assert!(same.eigenvalue_differences.iter().all(|&x| x == 0.0));
        assert!(same
            .first_in_second
            .iter()
            .all(|&x| (x - 1.0).abs() < 1e-10));
        // On the sphere the lowest 16 fields are the l = 1, 2 vector harmonics (λ = 2 and 6,
        // 6 and 10 fields): whole eigenspaces, so each discretization's fields lie almost
        // entirely in the other's span, and the eigenvalues agree to the discretization error.
        let whitney = sampled("whitney-galerkin", &mesh, 16);
        let other = BasisComparison::new(&mesh, &conforming, &whitney).unwrap();
        let worst = other
            .eigenvalue_differences
            .iter()
            .fold(0.0f64, |m, &x| m.max(x));
        assert!(worst > 0.0 && worst < 0.05, "{worst}");
        for captured in [&other.first_in_second, &other.second_in_first] {
            assert!(
                captured.iter().all(|&x| x > 0.95 && x < 1.0 + 1e-9),
                "{captured:?}"
            );
        }
    }
}
