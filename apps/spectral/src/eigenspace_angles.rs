//! Principal angles between the eigenspaces of two bases of one mesh, cluster by cluster.
//!
//! Where eigenvalues are (nearly) equal, single eigenfields are not determined — any rotation
//! within the eigenspace is as good — so two discretizations, or two runs of one, may return
//! different fields of the same space. Comparing them field by field would then report noise.
//! Instead the reference's eigenvalues are grouped into **clusters** and each cluster is
//! compared as a subspace:
//!
//! - **Clustering rule** ([`eigen_clusters`]): within one family (harmonic, integrable,
//!   co-integrable — the families are orthogonal, so each is clustered on its own), consecutive
//!   eigenvalues `λ_i ≤ λ_{i+1}` of the reference share a cluster when their relative gap
//!   `(λ_{i+1} − λ_i) / λ_{i+1}` is at most the tolerance (single linkage: a chain of small
//!   gaps is one cluster). All harmonic fields (eigenvalue 0) form one cluster.
//! - **Matching**: a cluster holding the reference's family positions `p..p+m` (the `p`-th to
//!   `p+m−1`-th field of that family) is compared with the other basis's fields at the same
//!   family positions.
//! - **Angles** ([`principal_angles`]): both sets of fields are orthonormalised in the
//!   area-weighted inner product of sampled fields (`⟨u, v⟩ = Σ_f |A_f| ⟨u_f, v_f⟩`, see
//!   [`crate::SampledBasis`]); the cosines of the principal angles are the singular values of
//!   the cross-Gram matrix `Q_aᵀ W Q_b`, the sines the square roots of the eigenvalues of
//!   `RᵀWR` with `R = Q_a − Q_b (Q_bᵀ W Q_a)` (`Q_a` the one of fewer columns). Angles below π/4 come from their sines, the
//!   others from their cosines, so that small angles are accurate to round-off (an arccosine
//!   of a cosine rounded to 1 would be ~1e-8 rad, not 0).
//!
//! An angle of 0 means the cluster's spaces coincide; π/2, that some direction of one is
//! orthogonal to the other. By the Davis–Kahan theorem the sine of the largest angle is at most
//! about (size of the discretizations' difference) / (the cluster's gap to its neighbours), so a
//! cluster with a small [`EigenCluster::gap_above`] may rotate away from its neighbour's.

use crate::basis::FieldFamily;
use faer::{Mat, MatRef, Side};

/// Default largest relative gap `(λ_{i+1} − λ_i) / λ_{i+1}` inside one cluster (1 %).
pub const DEFAULT_CLUSTER_TOLERANCE: f64 = 0.01;

/// A group of near-equal eigenvalues of one family of the reference basis.
#[derive(Debug, Clone, PartialEq)]
pub struct EigenCluster {
    /// The family of every field of the cluster.
    pub family: FieldFamily,
    /// Position of the cluster's first field within its family (0: the family's lowest).
    pub first: usize,
    /// Columns of the cluster's fields in the whole basis (ascending, consecutive in the
    /// family).
    pub columns: Vec<usize>,
    /// Smallest and largest eigenvalue of the cluster (1/length²).
    pub eigenvalues: (f64, f64),
    /// Relative gap `(λ_next − λ_max) / λ_next` to the family's next eigenvalue in the
    /// reference basis; `None` where the basis ends inside or right after the cluster (the
    /// next eigenvalue was not computed, so the cluster may be incomplete), or for the
    /// harmonic cluster.
    pub gap_above: Option<f64>,
}

impl EigenCluster {
    /// Number of fields in the cluster.
    pub fn size(&self) -> usize {
        self.columns.len()
    }
}

/// The clusters of a basis with `eigenvalues` (ascending) and `families` (same length), each
/// family on its own, `tolerance` the largest relative gap within a cluster (see the
/// [module](self)). Ordered by family (harmonic, integrable, co-integrable), then eigenvalue.
pub fn eigen_clusters(
    eigenvalues: &[f64],
    families: &[FieldFamily],
    tolerance: f64,
) -> Vec<EigenCluster> {
    let mut clusters = Vec::new();
    for family in [
        FieldFamily::Harmonic,
        FieldFamily::Integrable,
        FieldFamily::Cointegrable,
    ] {
        let columns: Vec<usize> = (0..families.len())
            .filter(|&j| families[j] == family)
            .collect();
        let mut start = 0;
        while start < columns.len() {
            let mut end = start + 1;
            while end < columns.len()
                && (family == FieldFamily::Harmonic
                    || joins(
                        eigenvalues[columns[end - 1]],
                        eigenvalues[columns[end]],
                        tolerance,
                    ))
            {
                end += 1;
            }
            let highest = eigenvalues[columns[end - 1]];
            let gap_above = (family != FieldFamily::Harmonic && end < columns.len())
                .then(|| relative_gap(highest, eigenvalues[columns[end]]));
            clusters.push(EigenCluster {
                family,
                first: start,
                columns: columns[start..end].to_vec(),
                eigenvalues: (eigenvalues[columns[start]], highest),
                gap_above,
            });
            start = end;
        }
    }
    clusters
}

/// `(upper − lower) / upper` (0 where both are 0).
fn relative_gap(lower: f64, upper: f64) -> f64 {
    if upper > 0.0 {
        (upper - lower) / upper
    } else {
        0.0
    }
}

/// Whether eigenvalues `lower ≤ upper` belong to one cluster.
fn joins(lower: f64, upper: f64, tolerance: f64) -> bool {
    relative_gap(lower, upper) <= tolerance
}

/// The columns of a basis holding positions `first..first+count` of `family`, or `None` if
/// the basis has fewer fields of that family.
pub fn family_columns(
    families: &[FieldFamily],
    family: FieldFamily,
    first: usize,
    count: usize,
) -> Option<Vec<usize>> {
    let columns: Vec<usize> = (0..families.len())
        .filter(|&j| families[j] == family)
        .skip(first)
        .take(count)
        .collect();
    (columns.len() == count).then_some(columns)
}

/// The principal angles (radians, ascending, `min(a.ncols(), b.ncols())` of them) between the
/// spans of the columns of `a` and of `b` (both `n × ·`), in the inner product
/// `⟨u, v⟩ = Σ_r weights[r] u_r v_r` (`weights` positive, `n` entries). `None` if the columns of
/// either are linearly dependent (a column in the span of the others, or zero).
pub fn principal_angles(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    weights: &[f64],
) -> Option<Vec<f64>> {
    let qa = weighted_orthonormal(a, weights)?;
    let qb = weighted_orthonormal(b, weights)?;
    let (qa, qb) = if qa.ncols() <= qb.ncols() {
        (qa, qb)
    } else {
        (qb, qa)
    };
    let wqb = Mat::from_fn(qb.nrows(), qb.ncols(), |r, c| weights[r] * qb[(r, c)]);
    let cross = qa.transpose() * &wqb; // p × q, p ≤ q: cosines are its singular values
    let mut cosines = cross.singular_values().ok()?;
    cosines.sort_by(|x, y| y.total_cmp(x));
    // R = Q_a − Q_b (Q_bᵀ W Q_a): the part of span(Q_a) outside span(Q_b); the eigenvalues of
    // Rᵀ W R are the squared sines of the p angles.
    let inside = &qb * cross.transpose();
    let residual = &qa - &inside;
    let wr = Mat::from_fn(residual.nrows(), residual.ncols(), |r, c| {
        weights[r] * residual[(r, c)]
    });
    let gram = residual.transpose() * &wr;
    let mut sines_squared = gram.self_adjoint_eigenvalues(Side::Lower).ok()?;
    sines_squared.sort_by(f64::total_cmp);
    Some(
        cosines
            .iter()
            .zip(&sines_squared)
            .map(|(&cos, &sin2)| {
                let sin = sin2.max(0.0).sqrt();
                if sin < std::f64::consts::FRAC_1_SQRT_2 {
                    sin.min(1.0).asin()
                } else {
                    cos.clamp(0.0, 1.0).acos()
                }
            })
            .collect(),
    )
}

/// The orthogonal projection of `v` (`n`) onto the span of the columns of `span` (`n × ·`) in
/// the inner product with `weights`: the element of the span closest to `v` (for pictures, a
/// field of one basis drawn beside the nearest field of another basis's eigenspace). `None` if
/// the columns are linearly dependent.
pub fn weighted_projection(span: MatRef<'_, f64>, weights: &[f64], v: &[f64]) -> Option<Vec<f64>> {
    let q = weighted_orthonormal(span, weights)?;
    let mut projection = vec![0.0; v.len()];
    for i in 0..q.ncols() {
        let c: f64 = (0..v.len()).map(|r| weights[r] * q[(r, i)] * v[r]).sum();
        for (r, p) in projection.iter_mut().enumerate() {
            *p += c * q[(r, i)];
        }
    }
    Some(projection)
}

/// The columns of `m` orthonormalised in the weighted inner product (Gram–Schmidt, each column
/// orthogonalised twice, which is enough for round-off orthogonality); `None` if a column
/// loses more than all but `1e-10` of its norm (dependent columns).
fn weighted_orthonormal(m: MatRef<'_, f64>, weights: &[f64]) -> Option<Mat<f64>> {
    let n = m.nrows();
    let inner = |q: &Mat<f64>, i: usize, v: &[f64]| -> f64 {
        (0..n).map(|r| weights[r] * q[(r, i)] * v[r]).sum()
    };
    let mut q = Mat::<f64>::zeros(n, m.ncols());
    for j in 0..m.ncols() {
        let mut v: Vec<f64> = (0..n).map(|r| m[(r, j)]).collect();
        let original: f64 = v.iter().zip(weights).map(|(x, w)| w * x * x).sum();
        for _ in 0..2 {
            for i in 0..j {
                let c = inner(&q, i, &v);
                for (r, x) in v.iter_mut().enumerate() {
                    *x -= c * q[(r, i)];
                }
            }
        }
        let norm2: f64 = v.iter().zip(weights).map(|(x, w)| w * x * x).sum();
        if !(norm2 > 1e-20 * original && norm2.is_finite()) {
            return None;
        }
        let norm = norm2.sqrt();
        for (r, x) in v.iter().enumerate() {
            q[(r, j)] = x / norm;
        }
    }
    Some(q)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    use crate::basis::FieldFamily::{Cointegrable as C, Harmonic as H, Integrable as I};

    #[test]
    fn near_equal_eigenvalues_of_one_family_form_a_cluster_and_families_are_apart() {
        let eigenvalues = [0.0, 0.0, 2.0, 2.0, 2.01, 2.0101, 6.0, 6.2];
        let families = [H, H, I, C, I, C, I, I];
        let clusters = eigen_clusters(&eigenvalues, &families, 0.01);
        let shapes: Vec<(FieldFamily, usize, Vec<usize>)> = clusters
            .iter()
            .map(|c| (c.family, c.first, c.columns.clone()))
            .collect();
        assert_eq!(
            shapes,
            vec![
                (H, 0, vec![0, 1]),
                (I, 0, vec![2, 4]),
                (I, 2, vec![6]),
                (I, 3, vec![7]),
                (C, 0, vec![3, 5]),
            ]
        );
        assert_eq!(clusters[0].gap_above, None, "harmonic");
        let gap = clusters[1].gap_above.unwrap();
        assert!((gap - (6.0 - 2.01) / 6.0).abs() < 1e-15);
        assert_eq!(clusters[3].gap_above, None, "the basis ends at the cluster");
        assert_eq!(clusters[4].eigenvalues, (2.0, 2.0101));
        assert_eq!(family_columns(&families, I, 2, 2), Some(vec![6, 7]));
        assert_eq!(family_columns(&families, C, 1, 2), None);
    }

    /// A weighted-orthonormal 4-dimensional frame in R^12 and its weights.
    fn frame() -> (Mat<f64>, Vec<f64>) {
        let weights: Vec<f64> = (0..12).map(|r| 0.5 + (r % 5) as f64 * 0.3).collect();
        let raw = Mat::from_fn(12, 4, |r, c| {
            ((r * 7 + c * 3) as f64 * 0.37).sin() + (c == r) as u8 as f64
        });
        (
            weighted_orthonormal(raw.as_ref(), &weights).unwrap(),
            weights,
        )
    }

    #[test]
    fn a_rotated_basis_of_an_eigenspace_has_zero_angles_and_an_orthogonal_one_right_angles() {
        let (q, weights) = frame();
        let space = q.subcols(0, 3);
        // The same space in another basis: a rotation mixing its three columns, scaled.
        let (s, c) = (0.6f64, 0.8f64);
        let rotation = Mat::from_fn(3, 3, |i, j| {
            [[c, -s, 0.0], [s * c, c * c, -s], [s * s, s * c, c]][i][j] * 2.5
        });
        let rotated = space * &rotation;
        let angles = principal_angles(space, rotated.as_ref(), &weights).unwrap();
        assert_eq!(angles.len(), 3);
        assert!(angles.iter().all(|&a| a.abs() < 1e-12), "{angles:?}");
        // The fourth column is orthogonal to the first three.
        let angles = principal_angles(q.subcols(0, 1), q.subcols(3, 1), &weights).unwrap();
        assert!((angles[0] - FRAC_PI_2).abs() < 1e-12, "{angles:?}");
        // A plane tilted by 0.3 rad out of span(q0, q1) towards q3: angles 0 and 0.3.
        let tilted = Mat::from_fn(12, 2, |r, j| match j {
            0 => q[(r, 0)],
            _ => 0.3f64.cos() * q[(r, 1)] + 0.3f64.sin() * q[(r, 3)],
        });
        let angles = principal_angles(q.subcols(0, 2), tilted.as_ref(), &weights).unwrap();
        assert!(
            angles[0].abs() < 1e-12 && (angles[1] - 0.3).abs() < 1e-12,
            "{angles:?}"
        );
        // The projection of q3 + 2 q0 onto span(q0, q1) is 2 q0.
        let v: Vec<f64> = (0..12).map(|r| q[(r, 3)] + 2.0 * q[(r, 0)]).collect();
        let p = weighted_projection(q.subcols(0, 2), &weights, &v).unwrap();
        assert!(
            (0..12).all(|r| (p[r] - 2.0 * q[(r, 0)]).abs() < 1e-12),
            "{p:?}"
        );
        // Dependent columns have no orthonormal basis.
        let dependent = Mat::from_fn(12, 2, |r, _| q[(r, 0)]);
        assert!(principal_angles(dependent.as_ref(), space, &weights).is_none());
    }
}
