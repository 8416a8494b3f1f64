//! Fields and potentials of a complex on an intrinsic triangulation, seen on the input mesh:
//! [`IntrinsicWhitneySampling`] (1-forms on intrinsic edges as tangent vectors at input points,
//! and per-input-face vectors as 1-forms) and [`IntrinsicEvaluation`] (0- and 2-forms at input
//! points), both through the common subdivision.

use crate::edge_averages::EdgeAverages;
use crate::face_geometry::FaceGeometry;
use crate::intrinsic_delaunay::IntrinsicInput;
use tvf_core::discretization::{
    check_face_vectors, check_length, DiscretizationError, FieldSampling, PointEvaluation,
    SamplingReproduction, TangentProjection,
};
use tvf_core::geometry::{cross, dot, scale, sub};
use tvf_core::intrinsic::corner_cotangents;
use tvf_core::{SurfacePoint, TriangleMesh};

/// Whitney interpolation of 1-forms on the edges of an intrinsic triangulation, sampled at points
/// of the **input** faces: `face_count()` is the input's, so a field file holds one 3D vector per
/// input face, the field's value at the input face's centroid ([`FieldSampling::to_face_vectors`]).
///
/// **Sampling** at an input point: the point is mapped to the intrinsic face it lies in (through
/// the cell of the common subdivision that contains it), the Whitney form of each side of that
/// face, `W_jk = λ_j ∇λ_k − λ_k ∇λ_j`, is evaluated there from the edge lengths (the Gram
/// matrix of the `∇λ` is `⟨∇λ_i, ∇λ_j⟩ = −cot θ_k / 2A`, `|∇λ_i|² = (cot θ_j + cot θ_k) / 2A`),
/// and the vector is carried to the input face by the cell's isometry (lengths and angles kept).
///
/// **Per-face vectors → 1-form** (the de Rham map): each input face's vector is projected onto its
/// plane, carried into every intrinsic face that overlaps the face and averaged there weighted by
/// the overlap areas (one tangent vector per intrinsic face); `x_e = ⟨u_t, p_k − p_j⟩` along each
/// side, averaged over the edge's faces. On a flat part of the input a constant vector comes back
/// exactly; across creases it is the area average (see [`SamplingReproduction::Approximate`]).
///
/// Edges fixed by the boundary condition (relative forms) have no Whitney form and get 0, as in
/// [`crate::WhitneySampling`].
#[derive(Debug, Clone)]
pub struct IntrinsicWhitneySampling {
    input: IntrinsicInput,
    input_faces: Vec<[usize; 3]>,
    positions: Vec<[f64; 3]>,
    frames: Vec<[[f64; 3]; 2]>,
    normals: Vec<[f64; 3]>,
    /// `∇λ_c` of the corners of every input face (3D, in the face plane, 1/length).
    input_gradients: Vec<[[f64; 3]; 3]>,
    /// `±1` per side of every intrinsic face: `+1` where it runs along its edge's reference
    /// direction.
    signs: Vec<[f64; 3]>,
    fixed_edges: Vec<bool>,
    /// [`FieldSampling::sample_weights`] at every input face's centroid, computed once: what
    /// [`FieldSampling::to_face_vectors`] applies to every field (a basis converts hundreds).
    centroid_weights: Vec<Vec<(usize, [f64; 3])>>,
}

impl IntrinsicWhitneySampling {
    /// The sampling of 1-forms on the triangulation of `input` on the faces of `mesh`; the edges
    /// flagged in `fixed_edges` (intrinsic `E` entries) are zero in every field. Fails on a
    /// degenerate input face.
    pub fn new(
        mesh: &TriangleMesh,
        input: &IntrinsicInput,
        fixed_edges: Vec<bool>,
    ) -> Result<Self, DiscretizationError> {
        let geometry = FaceGeometry::new(mesh)?;
        let input_gradients = mesh
            .faces()
            .iter()
            .enumerate()
            .map(|(t, face)| {
                let p = face.map(|i| mesh.positions()[i]);
                let two_area = 2.0 * geometry.areas[t];
                std::array::from_fn(|c| {
                    let opposite = sub(p[(c + 2) % 3], p[(c + 1) % 3]);
                    scale(cross(geometry.normals[t], opposite), 1.0 / two_area)
                })
            })
            .collect();
        let tri = &input.triangulation;
        let signs = (0..tri.face_count())
            .map(|t| {
                tri.face_edge_orientations(t)
                    .map(|f| if f { 1.0 } else { -1.0 })
            })
            .collect();
        let mut sampling = Self {
            input: input.clone(),
            input_faces: mesh.faces().to_vec(),
            positions: mesh.positions().to_vec(),
            frames: geometry.frames,
            normals: geometry.normals,
            input_gradients,
            signs,
            fixed_edges,
            centroid_weights: Vec::new(),
        };
        sampling.centroid_weights = (0..mesh.face_count())
            .map(|f| sampling.sample_weights(&sampling.centroid(f)))
            .collect();
        Ok(sampling)
    }

    /// A displacement of barycentric coordinates of input face `f` as a 3D vector.
    fn input_vector(&self, f: usize, d: [f64; 3]) -> [f64; 3] {
        let p = self.input_faces[f].map(|i| self.positions[i]);
        std::array::from_fn(|k| d[0] * p[0][k] + d[1] * p[1][k] + d[2] * p[2][k])
    }

    /// The tangent vector of every intrinsic face (as a displacement of its barycentric
    /// coordinates): the area average of the input faces' vectors `vectors` over the cells of
    /// the face.
    fn intrinsic_face_vectors(&self, vectors: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let overlay = &self.input.overlay;
        (0..overlay.intrinsic_face_count())
            .map(|t| {
                let mut sum = [0.0; 3];
                let mut area = 0.0;
                for &i in overlay.intrinsic_face_cells(t) {
                    let cell = overlay.cell(i);
                    let gradients = &self.input_gradients[cell.input_face];
                    let v = vectors[cell.input_face];
                    let d: [f64; 3] = std::array::from_fn(|c| dot(gradients[c], v));
                    if let Some(there) = overlay.to_intrinsic_displacement(i, d) {
                        for k in 0..3 {
                            sum[k] += cell.area * there[k];
                        }
                        area += cell.area;
                    }
                }
                if area > 0.0 {
                    sum.map(|x| x / area)
                } else {
                    [0.0; 3]
                }
            })
            .collect()
    }
}

/// `⟨∇λ_i, ∇λ_j⟩` of a triangle with side lengths `lengths` (`l_c` opposite corner `c`), from its
/// cotangents and area (1/length²).
fn barycentric_gram(lengths: [f64; 3]) -> [[f64; 3]; 3] {
    let cot = corner_cotangents(lengths);
    let two_area = 2.0 * tvf_core::intrinsic::triangle_area(lengths);
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            if i == j {
                (cot[(i + 1) % 3] + cot[(i + 2) % 3]) / two_area
            } else {
                -cot[3 - i - j] / two_area
            }
        })
    })
}

impl FieldSampling for IntrinsicWhitneySampling {
    fn face_count(&self) -> usize {
        self.input_faces.len()
    }

    fn field_dimension(&self) -> usize {
        self.input.triangulation.edge_count()
    }

    fn frame(&self, face: usize) -> [[f64; 3]; 2] {
        self.frames[face]
    }

    fn normal(&self, face: usize) -> [f64; 3] {
        self.normals[face]
    }

    fn centroid(&self, face: usize) -> SurfacePoint {
        SurfacePoint::barycentric(face, [1.0 / 3.0; 3])
    }

    fn reproduction(&self) -> SamplingReproduction {
        SamplingReproduction::Approximate
    }

    fn sample_weights(&self, point: &SurfacePoint) -> Vec<(usize, [f64; 3])> {
        let (cell, q) = self.input.locate(point.face, point.triangle_coordinates());
        let tri = &self.input.triangulation;
        let t = q.face;
        let b = q.barycentric;
        let gram = barycentric_gram(tri.face_lengths(t));
        let edges = tri.face_edges(t);
        (0..3)
            .filter(|&c| !self.fixed_edges[edges[c]])
            .map(|c| {
                let (j, k) = ((c + 1) % 3, (c + 2) % 3);
                let sign = self.signs[t][c];
                let d: [f64; 3] =
                    std::array::from_fn(|m| sign * (b[j] * gram[m][k] - b[k] * gram[m][j]));
                let on_input = self
                    .input
                    .overlay
                    .to_input_displacement(cell, d)
                    .unwrap_or([0.0; 3]);
                (edges[c], self.input_vector(point.face, on_input))
            })
            .collect()
    }

    fn to_face_vectors(&self, field: &[f64]) -> Result<Vec<[f64; 3]>, DiscretizationError> {
        check_length("field coefficients", self.field_dimension(), field.len())?;
        Ok(self
            .centroid_weights
            .iter()
            .map(|weights| {
                let mut v = [0.0; 3];
                for &(i, w) in weights {
                    for k in 0..3 {
                        v[k] += w[k] * field[i];
                    }
                }
                v
            })
            .collect())
    }

    fn from_face_vectors(
        &self,
        vectors: &[[f64; 3]],
    ) -> Result<TangentProjection, DiscretizationError> {
        check_face_vectors(self.face_count(), vectors)?;
        let tri = &self.input.triangulation;
        let face_vectors = self.intrinsic_face_vectors(vectors);
        let mut averages = EdgeAverages::new(tri.edge_count());
        for (t, u) in face_vectors.iter().enumerate() {
            let l2 = tri.face_lengths(t).map(|l| l * l);
            for (c, e) in tri.face_edges(t).into_iter().enumerate() {
                let (j, k) = ((c + 1) % 3, (c + 2) % 3);
                // ⟨u, p_k − p_j⟩ with u = Σ u_m (p_m − p_j): |p_k − p_j|² = l_c², and
                // ⟨p_c − p_j, p_k − p_j⟩ = (l_k² + l_c² − l_j²) / 2.
                let along = u[k] * l2[c] + u[c] * (l2[k] + l2[c] - l2[j]) / 2.0;
                averages.add(e, self.signs[t][c] * along);
            }
        }
        let field = averages.means(&self.fixed_edges);
        let normal_parts = vectors
            .iter()
            .zip(&self.normals)
            .map(|(&v, &n)| dot(v, n))
            .collect();
        Ok(TangentProjection {
            field,
            normal_parts,
        })
    }
}

/// Point evaluation of the 0- and 2-forms of a complex on an intrinsic triangulation at points of
/// the input faces: a 0-form is interpolated linearly in the intrinsic face the point lies in
/// (its corners, which may include inserted vertices), a 2-form is constant on it.
#[derive(Debug, Clone)]
pub struct IntrinsicEvaluation {
    input: IntrinsicInput,
}

impl IntrinsicEvaluation {
    /// The evaluation at the input points of `input`.
    pub fn new(input: &IntrinsicInput) -> Self {
        Self {
            input: input.clone(),
        }
    }
}

impl PointEvaluation for IntrinsicEvaluation {
    fn potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        let (_, q) = self.input.locate(point.face, point.triangle_coordinates());
        let corners = self.input.triangulation.faces()[q.face];
        (0..3).map(|c| (corners[c], q.barycentric[c])).collect()
    }

    fn co_potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        let (_, q) = self.input.locate(point.face, point.triangle_coordinates());
        vec![(q.face, 1.0)]
    }
}
