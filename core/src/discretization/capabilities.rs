//! The small capabilities a complex may offer besides its five matrices. Generic code asks only
//! for the one it uses, through [`super::HodgeComplex::sampling`],
//! [`super::HodgeComplex::rotation`] and [`super::HodgeComplex::point_evaluation`].

use super::{DiscretizationError, FaceFrames};
use crate::SurfacePoint;
use sprs::CsMat;

/// The result of turning 3D vectors (one per face) into a field.
#[derive(Debug, Clone, PartialEq)]
pub struct TangentProjection {
    /// The field (`n1` coefficients of the complex).
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

/// What a complex's sampling reproduces exactly, stated by the complex and checked by the
/// conformance suite (`tvf-conformance`'s sampling checks) instead of assumed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SamplingReproduction {
    /// The gradient `d0 φ` of a linear function `φ(x) = ⟨v, x⟩` (sampled at the potential
    /// nodes) samples back to `v` projected onto each face's plane, at every point of the face;
    /// and so does the field [`FieldSampling::from_face_vectors`] makes of the constant vector
    /// `v` on every face (piecewise constant face fields, DEC and Whitney 1-forms on triangles).
    ConstantVectors,
    /// Only the first half: the gradient of a linear function samples back to `v` projected
    /// onto each face's plane (for a polygon, the plane normal to its vector area: the sharp of
    /// the 1-form of a constant field, de Goes, Butts, Desbrun 2020 §4); `from_face_vectors`
    /// averages per-face projections, which agree with that only where faces are planar.
    LinearGradients,
    /// Neither exactly: the sampling of a complex on an intrinsic triangulation, which carries
    /// vectors between intrinsic and input faces. Both halves hold where the input is flat
    /// (within a planar region of the input); across creases they hold to the discretization's
    /// order only. The conformance suite's reproduction checks do not apply.
    Approximate,
}

/// Sampling: a field seen as a 3D tangent vector at a point of a face ([`SurfacePoint`]: a face
/// and weights over its corners), as a linear map, and its inverse on per-face vectors. It gives
/// field I/O (one 3D vector per face), rendering, vector constraints and the editor.
pub trait FieldSampling: Send + Sync {
    /// The frame and unit normal of every face ([`FaceFrames`]: `F` entries), in which
    /// [`FieldSampling::sample_frame_weights`] and [`FieldSampling::from_face_vectors`] read
    /// per-face vectors.
    fn face_frames(&self) -> &FaceFrames;

    /// Number of faces `F` of the mesh.
    fn face_count(&self) -> usize {
        self.face_frames().len()
    }

    /// Number of field coefficients `n1`.
    fn field_dimension(&self) -> usize;

    /// An orthonormal, positively oriented frame `[e1, e2]` of face `t`'s plane (`e2 = n × e1`;
    /// [`FaceFrames`] states the conventions for triangles and polygons).
    fn frame(&self, face: usize) -> [[f64; 3]; 2] {
        self.face_frames().frame(face)
    }

    /// The unit normal of face `t` (counter-clockwise orientation; for a polygon, along its vector
    /// area).
    fn normal(&self, face: usize) -> [f64; 3] {
        self.face_frames().normal(face)
    }

    /// The point of face `face` where [`FieldSampling::to_face_vectors`] samples: its corner
    /// average (for a triangle its centroid, barycentric `[1/3; 3]`; [`FaceFrames::centroid`]).
    fn centroid(&self, face: usize) -> SurfacePoint {
        self.face_frames().centroid(face)
    }

    /// What this sampling reproduces exactly ([`SamplingReproduction`]; the suite checks it).
    fn reproduction(&self) -> SamplingReproduction {
        SamplingReproduction::ConstantVectors
    }

    /// The sampled vector at `point` as a linear map: `v = Σ w_i x_i` over the returned
    /// `(i, w_i)`, `w_i` a 3D vector in the face plane (pointwise units). Panics if the point's
    /// face is out of range or its weights do not fit the face (callers check points with
    /// [`crate::SurfaceMesh::check_point`]).
    fn sample_weights(&self, point: &SurfacePoint) -> Vec<(usize, [f64; 3])>;

    /// The sampled vector in the coordinates of the face frame ([`FieldSampling::frame`]): the
    /// same linear map as [`FieldSampling::sample_weights`] with each weight `w_i` given as
    /// `(w_i·e1, w_i·e2)`. Discretizations whose coefficients are frame coordinates override it
    /// to return exact unit weights.
    fn sample_frame_weights(&self, point: &SurfacePoint) -> Vec<(usize, [f64; 2])> {
        let [e1, e2] = self.frame(point.face);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        self.sample_weights(point)
            .into_iter()
            .map(|(i, w)| (i, [dot(w, e1), dot(w, e2)]))
            .collect()
    }

    /// [`FieldSampling::from_face_vectors`] of `vectors`, which hold one vector per face (`F`
    /// entries, checked by the caller): each vector projected onto its face plane and turned
    /// into coefficients (each discretization documents how), with the dropped normal
    /// components alongside.
    fn project_face_vectors(&self, vectors: &[[f64; 3]]) -> TangentProjection;

    /// A field from one 3D vector per face (`F` entries): each vector is projected onto its face
    /// plane and turned into coefficients ([`FieldSampling::project_face_vectors`]); the dropped
    /// normal components are returned alongside. Fails if `vectors` does not have `F` entries.
    // Named as the inverse of `to_face_vectors`; it needs `self` for the geometry.
    #[allow(clippy::wrong_self_convention)]
    fn from_face_vectors(
        &self,
        vectors: &[[f64; 3]],
    ) -> Result<TangentProjection, DiscretizationError> {
        check_face_vectors(self.face_count(), vectors)?;
        Ok(self.project_face_vectors(vectors))
    }

    /// One 3D vector per face (`F` entries): the field sampled at each face's centroid
    /// ([`FieldSampling::centroid`]).
    fn to_face_vectors(&self, field: &[f64]) -> Result<Vec<[f64; 3]>, DiscretizationError> {
        check_length("field coefficients", self.field_dimension(), field.len())?;
        Ok((0..self.face_count())
            .map(|t| {
                let mut v = [0.0; 3];
                for (i, w) in self.sample_weights(&self.centroid(t)) {
                    for k in 0..3 {
                        v[k] += w[k] * field[i];
                    }
                }
                v
            })
            .collect())
    }
}

/// A rotation `J` of fields by +π/2 in every tangent plane (`n1 × n1`, `M1`-orthogonal,
/// `J² = −I`). Piecewise constant face fields have one; with it the complex also has "the other
/// family" of divergence and curl (see [`super::HodgeOperators::other_divergence`]).
pub trait FieldRotation: Send + Sync {
    /// The matrix `J` (`n1 × n1`).
    fn rotation(&self) -> &CsMat<f64>;
}

/// Evaluation of potentials and co-potentials at a point of a face: the interpolation weights of
/// each space. Gives divergence and curl constraints at points, and face colours.
pub trait PointEvaluation: Send + Sync {
    /// The potential nodes whose basis functions are non-zero at `point`, with their values
    /// there (the weights sum to 1). Panics as [`FieldSampling::sample_weights`] does.
    fn potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)>;

    /// The same for the co-potential space.
    fn co_potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)>;
}

/// Checks the input of [`FieldSampling::from_face_vectors`]: one vector per face (`face_count`
/// of them), every component finite.
pub fn check_face_vectors(
    face_count: usize,
    vectors: &[[f64; 3]],
) -> Result<(), DiscretizationError> {
    check_length("per-face vectors", face_count, vectors.len())?;
    match vectors
        .iter()
        .position(|v| v.iter().any(|x| !x.is_finite()))
    {
        Some(index) => Err(DiscretizationError::NonFinite {
            what: "per-face vectors",
            index,
        }),
        None => Ok(()),
    }
}

/// Fails with [`DiscretizationError::DimensionMismatch`] unless `found == expected`.
pub fn check_length(
    what: &'static str,
    expected: usize,
    found: usize,
) -> Result<(), DiscretizationError> {
    if expected == found {
        Ok(())
    } else {
        Err(DiscretizationError::DimensionMismatch {
            what,
            expected,
            found,
        })
    }
}
