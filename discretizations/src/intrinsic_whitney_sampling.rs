//! [`IntrinsicWhitneySampling`]: Whitney interpolation of 1-forms on the edges of an intrinsic
//! triangulation ([`IntrinsicWhitneyForms`]), sampled at points of the input faces.

use crate::edge_averages::EdgeAverages;
use crate::intrinsic_delaunay::IntrinsicInput;
use crate::intrinsic_sampling::{IntrinsicReconstruction, IntrinsicSampling};
use tvf_core::discretization::DiscretizationError;
use tvf_core::intrinsic::{corner_cotangents, IntrinsicTriangulation};
use tvf_core::TriangleMesh;

/// Whitney interpolation of 1-forms on the edges of an intrinsic triangulation, sampled at points
/// of the **input** faces ([`IntrinsicSampling`]).
///
/// In an intrinsic face, the Whitney form of each side, `W_jk = λ_j ∇λ_k − λ_k ∇λ_j`, is
/// evaluated from the edge lengths (the Gram matrix of the `∇λ` is
/// `⟨∇λ_i, ∇λ_j⟩ = −cot θ_k / 2A`, `|∇λ_i|² = (cot θ_j + cot θ_k) / 2A`). Per-face vectors become a
/// 1-form by the de Rham map: `x_e = ⟨u_t, p_k − p_j⟩` along each side of the intrinsic faces'
/// vectors `u_t`, averaged over the edge's faces.
///
/// Edges fixed by the boundary condition (relative forms) have no Whitney form and get 0, as in
/// [`crate::WhitneySampling`].
pub type IntrinsicWhitneySampling = IntrinsicSampling<IntrinsicWhitneyForms>;

/// The Whitney 1-forms of an intrinsic triangulation as an [`IntrinsicReconstruction`]: a field
/// is one value per intrinsic edge (its integral along the edge's reference direction).
#[derive(Debug, Clone)]
pub struct IntrinsicWhitneyForms {
    /// `±1` per side of every intrinsic face: `+1` where it runs along its edge's reference
    /// direction.
    signs: Vec<[f64; 3]>,
    /// Edges whose value the boundary condition fixes to zero (intrinsic `E` entries).
    fixed_edges: Vec<bool>,
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
        let tri = &input.triangulation;
        let signs = (0..tri.face_count())
            .map(|t| {
                tri.face_edge_orientations(t)
                    .map(|f| if f { 1.0 } else { -1.0 })
            })
            .collect();
        Self::with_reconstruction(mesh, input, IntrinsicWhitneyForms { signs, fixed_edges })
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

impl IntrinsicReconstruction for IntrinsicWhitneyForms {
    fn field_dimension(&self, triangulation: &IntrinsicTriangulation) -> usize {
        triangulation.edge_count()
    }

    /// The Whitney forms of the face's sides that the boundary condition leaves free.
    fn face_weights(
        &self,
        triangulation: &IntrinsicTriangulation,
        t: usize,
        b: [f64; 3],
    ) -> Vec<(usize, [f64; 3])> {
        let gram = barycentric_gram(triangulation.face_lengths(t));
        let edges = triangulation.face_edges(t);
        (0..3)
            .filter(|&c| !self.fixed_edges[edges[c]])
            .map(|c| {
                let (j, k) = ((c + 1) % 3, (c + 2) % 3);
                let sign = self.signs[t][c];
                let d: [f64; 3] =
                    std::array::from_fn(|m| sign * (b[j] * gram[m][k] - b[k] * gram[m][j]));
                (edges[c], d)
            })
            .collect()
    }

    /// The de Rham map of the faces' vectors, 0 on fixed edges.
    fn field_of_displacements(
        &self,
        triangulation: &IntrinsicTriangulation,
        displacements: &[[f64; 3]],
    ) -> Vec<f64> {
        let mut averages = EdgeAverages::new(triangulation.edge_count());
        for (t, u) in displacements.iter().enumerate() {
            let l2 = triangulation.face_lengths(t).map(|l| l * l);
            for (c, e) in triangulation.face_edges(t).into_iter().enumerate() {
                let (j, k) = ((c + 1) % 3, (c + 2) % 3);
                // ⟨u, p_k − p_j⟩ with u = Σ u_m (p_m − p_j): |p_k − p_j|² = l_c², and
                // ⟨p_c − p_j, p_k − p_j⟩ = (l_k² + l_c² − l_j²) / 2.
                let along = u[k] * l2[c] + u[c] * (l2[k] + l2[c] - l2[j]) / 2.0;
                averages.add(e, self.signs[t][c] * along);
            }
        }
        averages.means(&self.fixed_edges)
    }
}
