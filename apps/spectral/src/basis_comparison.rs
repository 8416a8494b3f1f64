//! [`BasisComparison`]: how two discretizations' Fourier bases of the same mesh agree — their
//! eigenvalues index by index (overall and within each family), how much of each eigenfield of
//! one lies in the span of the other's, and the principal angles between their eigenspaces,
//! cluster by cluster ([`crate::eigenspace_angles`]). Fields of different discretizations live in different coefficient spaces, so both
//! are compared as what they mean on the surface: one tangent vector per face, sampled at the
//! face's centroid, with the area-weighted inner product `⟨u, v⟩ = Σ_f |A_f| ⟨u_f, v_f⟩`.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use thiserror::Error;
use tvf_core::discretization::{DiscretizationError, HodgeComplex, HodgeOperators};
use tvf_core::SurfaceMesh;

use crate::basis::{FieldFamily, SpectralBasis};
use crate::eigenspace_angles::{eigen_clusters, family_columns, principal_angles, EigenCluster};

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
/// `3f..3f+3` its vector at face `f`'s centroid), with its eigenvalues (`d`, ascending) and
/// their families.
pub struct SampledBasis {
    /// What names the basis in comparisons: the complex's id unless the caller renames it.
    pub id: String,
    /// Eigenvalues, ascending, in 1/length².
    pub eigenvalues: Vec<f64>,
    /// The family of each field (`d`).
    pub families: Vec<FieldFamily>,
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
            families: basis.families().to_vec(),
            vectors,
        })
    }

    /// The sampled fields at `columns`, `3F × columns.len()`.
    pub fn columns(&self, columns: &[usize]) -> Mat<f64> {
        Mat::from_fn(self.vectors.nrows(), columns.len(), |r, c| {
            self.vectors[(r, columns[c])]
        })
    }

    /// The eigenvalues of the fields of `family`, ascending.
    pub fn family_eigenvalues(&self, family: FieldFamily) -> Vec<f64> {
        self.eigenvalues
            .iter()
            .zip(&self.families)
            .filter(|(_, &f)| f == family)
            .map(|(&x, _)| x)
            .collect()
    }
}

/// One cluster of near-equal eigenvalues of the first basis compared as a subspace with the
/// second basis's fields at the same positions of the family.
#[derive(Debug, Clone)]
pub struct ClusterComparison {
    /// The cluster of the first basis.
    pub cluster: EigenCluster,
    /// Columns of the second basis at the cluster's family positions; `None` where the second
    /// basis has fewer fields of the family (its K lowest fields split differently).
    pub other_columns: Option<Vec<usize>>,
    /// Principal angles between the two spans, radians, ascending (`cluster.size()` of them);
    /// empty where `other_columns` is `None`.
    pub angles: Vec<f64>,
}

impl ClusterComparison {
    /// The largest principal angle (radians), `None` if the cluster was not compared.
    pub fn largest_angle(&self) -> Option<f64> {
        self.angles.iter().copied().reduce(f64::max)
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
    /// Per family (integrable, co-integrable), the relative differences of the family's
    /// eigenvalues position by position (as many as the smaller basis has of it).
    pub integrable_differences: Vec<f64>,
    /// The same for the co-integrable family.
    pub cointegrable_differences: Vec<f64>,
    /// Every cluster of the first basis (harmonic, integrable, co-integrable; see
    /// [`crate::eigenspace_angles`]) with its principal angles to the second's span.
    pub clusters: Vec<ClusterComparison>,
}

impl BasisComparison {
    /// Compares `a` and `b`, sampled on `mesh`; `cluster_tolerance` is the largest relative gap
    /// of eigenvalues within a cluster of `a` (e.g.
    /// [`crate::eigenspace_angles::DEFAULT_CLUSTER_TOLERANCE`]).
    pub fn new(
        mesh: &SurfaceMesh,
        a: &SampledBasis,
        b: &SampledBasis,
        cluster_tolerance: f64,
    ) -> Result<Self, BasisComparisonError> {
        let d = a.eigenvalues.len().min(b.eigenvalues.len());
        let weights = area_weights(mesh);
        let weighted = |m: &Mat<f64>| Mat::from_fn(m.nrows(), d, |r, c| weights[r] * m[(r, c)]);
        let va = a.vectors.subcols(0, d).to_owned();
        let vb = b.vectors.subcols(0, d).to_owned();
        let (wa, wb) = (weighted(&va), weighted(&vb));
        let gram_a = va.transpose() * &wa;
        let gram_b = vb.transpose() * &wb;
        let cross = vb.transpose() * &wa; // d × d: ⟨b_i, a_j⟩
        let first_in_second = captured(&gram_b, &cross, &gram_a, &b.id)?;
        let second_in_first = captured(&gram_a, &cross.transpose().to_owned(), &gram_b, &a.id)?;
        let family_differences = |family| {
            relative_differences(&a.family_eigenvalues(family), &b.family_eigenvalues(family))
        };
        Ok(Self {
            first: a.id.clone(),
            second: b.id.clone(),
            eigenvalue_differences: relative_differences(&a.eigenvalues, &b.eigenvalues),
            first_in_second,
            second_in_first,
            integrable_differences: family_differences(FieldFamily::Integrable),
            cointegrable_differences: family_differences(FieldFamily::Cointegrable),
            clusters: cluster_comparisons(a, b, &weights, cluster_tolerance)?,
        })
    }
}

/// The weights of the area-weighted inner product of sampled fields (`3F`: each face's area
/// three times, one per component of its vector).
pub fn area_weights(mesh: &SurfaceMesh) -> Vec<f64> {
    (0..mesh.face_count())
        .flat_map(|f| [mesh.face_area(f); 3])
        .collect()
}

/// `|x − y| / max(|x|, |y|)` position by position over the shorter of `a` and `b`, 0 where both
/// are zero to `ZERO_EIGENVALUE_RELATIVE` of the largest compared value.
pub fn relative_differences(a: &[f64], b: &[f64]) -> Vec<f64> {
    let d = a.len().min(b.len());
    let largest = a[..d]
        .iter()
        .chain(&b[..d])
        .fold(0.0f64, |m, x| m.max(x.abs()));
    (0..d)
        .map(|i| {
            let (x, y) = (a[i], b[i]);
            let scale = x.abs().max(y.abs());
            if scale <= ZERO_EIGENVALUE_RELATIVE * largest {
                0.0
            } else {
                (x - y).abs() / scale
            }
        })
        .collect()
}

/// The clusters of `a` and their principal angles to `b`'s fields at the same family
/// positions, in the inner product with per-row `weights`.
fn cluster_comparisons(
    a: &SampledBasis,
    b: &SampledBasis,
    weights: &[f64],
    tolerance: f64,
) -> Result<Vec<ClusterComparison>, BasisComparisonError> {
    eigen_clusters(&a.eigenvalues, &a.families, tolerance)
        .into_iter()
        .map(
            |cluster| -> Result<ClusterComparison, BasisComparisonError> {
                let other_columns =
                    family_columns(&b.families, cluster.family, cluster.first, cluster.size());
                let angles = match &other_columns {
                    Some(columns) => {
                        let (va, vb) = (a.columns(&cluster.columns), b.columns(columns));
                        principal_angles(va.as_ref(), vb.as_ref(), weights).ok_or_else(|| {
                            BasisComparisonError::DependentFields {
                                id: format!("{} or {}", a.id, b.id),
                            }
                        })?
                    }
                    None => Vec::new(),
                };
                Ok(ClusterComparison {
                    cluster,
                    other_columns,
                    angles,
                })
            },
        )
        .collect()
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
        let same = BasisComparison::new(&mesh, &conforming, &conforming, 0.01).unwrap();
        assert!(same.eigenvalue_differences.iter().all(|&x| x == 0.0));
        assert!(same
            .first_in_second
            .iter()
            .all(|&x| (x - 1.0).abs() < 1e-10));
        // On the sphere the lowest 16 fields are the l = 1, 2 vector harmonics (λ = 2 and 6,
        // 6 and 10 fields): whole eigenspaces, so each discretization's fields lie almost
        // entirely in the other's span, and the eigenvalues agree to the discretization error.
        let whitney = sampled("whitney-galerkin", &mesh, 16);
        let other = BasisComparison::new(&mesh, &conforming, &whitney, 0.01).unwrap();
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
        // The icosahedral symmetry keeps l = 1 and l = 2 exactly degenerate: per family one
        // cluster of 3 and one of 5, each compared as a whole with small angles; the last
        // clusters end the basis, so their gap above is unknown.
        let shapes: Vec<(FieldFamily, usize)> = other
            .clusters
            .iter()
            .map(|c| (c.cluster.family, c.cluster.size()))
            .collect();
        use crate::basis::FieldFamily::{Cointegrable, Integrable};
        assert_eq!(
            shapes,
            [
                (Integrable, 3),
                (Integrable, 5),
                (Cointegrable, 3),
                (Cointegrable, 5)
            ]
        );
        for c in &other.clusters {
            let largest = c.largest_angle().unwrap();
            assert!(largest > 0.0 && largest < 0.1, "{c:?}");
            assert_eq!(c.cluster.gap_above.is_some(), c.cluster.size() == 3);
        }
        for c in &same.clusters {
            assert!(c.largest_angle().unwrap() < 1e-10, "{c:?}");
        }
        assert_eq!(other.integrable_differences.len(), 8);
        assert_eq!(other.cointegrable_differences.len(), 8);
    }
}
