//! The [`FieldSpace`] trait: piecewise constant tangent vector fields `X_h`.

use super::DiscretizationError;
use sprs::CsMat;

/// The result of converting 3D vectors (one per face) into a tangent field.
#[derive(Debug, Clone, PartialEq)]
pub struct TangentProjection {
    /// The tangent field, `2F` pointwise coefficients in the face frames.
    pub field: Vec<f64>,
    /// The dropped normal component of every input vector (`F` entries, signed, same units as
    /// the input): `v · n_t`. Callers decide whether a large value means bad input.
    pub normal_parts: Vec<f64>,
}

impl TangentProjection {
    /// Largest absolute dropped normal component (0 for an empty mesh).
    pub fn max_normal_part(&self) -> f64 {
        self.normal_parts.iter().fold(0.0, |m, x| m.max(x.abs()))
    }
}

/// The space of piecewise constant tangent vector fields: one tangent vector per face, stored as
/// `(x[2t], x[2t+1])` in an orthonormal, positively oriented frame `(e1, e2)` of face `t`.
///
/// Coefficients are **pointwise** (a vector, not a vector times area).
pub trait FieldSpace {
    /// Number of faces `F`.
    fn face_count(&self) -> usize;

    /// Dimension `2F`.
    fn dimension(&self) -> usize {
        2 * self.face_count()
    }

    /// Diagonal of the mass matrix `M_X` (`2F` entries: the face area `A_t` twice per face,
    /// units of area), so that `xᵀ M_X y = ∫ ⟨x, y⟩`.
    fn mass(&self) -> &[f64];

    /// The rotation `J` by +π/2 in every tangent plane (`2F × 2F`, block diagonal with blocks
    /// `[[0, −1], [1, 0]]`, i.e. `(a, b) ↦ (−b, a)`); orthogonal, `J² = −I`, `Jᵀ M_X J = M_X`.
    fn rotation(&self) -> &CsMat<f64>;

    /// `J x` without forming a matrix product (length `2F`).
    fn rotate(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; x.len()];
        for (out, pair) in y.chunks_exact_mut(2).zip(x.chunks_exact(2)) {
            out[0] = -pair[1];
            out[1] = pair[0];
        }
        y
    }

    /// The frame `[e1, e2]` of face `t` as unit 3D vectors (`e2 = n_t × e1`).
    fn frame(&self, face: usize) -> [[f64; 3]; 2];

    /// The unit normal `n_t` of face `t` (counter-clockwise orientation).
    fn normal(&self, face: usize) -> [f64; 3];

    /// Connected component of every face (`F` entries).
    fn face_components(&self) -> &[usize];

    /// One 3D vector per face (`F` entries) from a field of `2F` coefficients.
    fn to_vectors(&self, field: &[f64]) -> Result<Vec<[f64; 3]>, DiscretizationError> {
        if field.len() != self.dimension() {
            return Err(DiscretizationError::DimensionMismatch {
                what: "tangent field coefficients",
                expected: self.dimension(),
                found: field.len(),
            });
        }
        Ok((0..self.face_count())
            .map(|t| {
                let [e1, e2] = self.frame(t);
                let (a, b) = (field[2 * t], field[2 * t + 1]);
                [
                    a * e1[0] + b * e2[0],
                    a * e1[1] + b * e2[1],
                    a * e1[2] + b * e2[2],
                ]
            })
            .collect())
    }

    /// A tangent field from one 3D vector per face (`F` entries): each vector is projected onto
    /// its face's plane; the dropped normal components are returned alongside.
    // Named as the inverse of `to_vectors`; it needs `self` for the frames.
    #[allow(clippy::wrong_self_convention)]
    fn from_vectors(&self, vectors: &[[f64; 3]]) -> Result<TangentProjection, DiscretizationError> {
        if vectors.len() != self.face_count() {
            return Err(DiscretizationError::DimensionMismatch {
                what: "per-face vectors",
                expected: self.face_count(),
                found: vectors.len(),
            });
        }
        if let Some(index) = vectors
            .iter()
            .position(|v| v.iter().any(|x| !x.is_finite()))
        {
            return Err(DiscretizationError::NonFinite {
                what: "per-face vectors",
                index,
            });
        }
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let mut field = Vec::with_capacity(self.dimension());
        let mut normal_parts = Vec::with_capacity(self.face_count());
        for (t, &v) in vectors.iter().enumerate() {
            let [e1, e2] = self.frame(t);
            field.push(dot(v, e1));
            field.push(dot(v, e2));
            normal_parts.push(dot(v, self.normal(t)));
        }
        Ok(TangentProjection {
            field,
            normal_parts,
        })
    }
}
