//! The [`FunctionSpace`] trait: a finite element space of scalar functions on a mesh, the building
//! block of [`crate::FiniteElementComplex`].

use sprs::CsMat;
use tvf_core::discretization::{DiscretizationError, Mass, NodeKind};

/// A space of piecewise linear scalar functions on a triangle mesh, represented by nodal values
/// (Lagrange P1: one value per vertex; Crouzeix–Raviart: one value per edge midpoint).
///
/// Coefficients are **pointwise** nodal values. The space knows its lumped mass (the plug-in
/// point for mass lumping), the mass matrix the complex uses (that lumped one, or a consistent
/// one), and its gradient into the piecewise constant face fields `X_h`, in the
/// face frames of [`crate::FaceFields`] (`e1 = normalize(p_{i1} − p_{i0})`,
/// `e2 = n × e1`, see `docs/conventions.md`).
pub trait FunctionSpace {
    /// Short human-readable name, e.g. `"Lagrange P1"`.
    fn name(&self) -> &str;

    /// The mesh element of each node (vertices for P1, edges for Crouzeix–Raviart).
    fn node_kind(&self) -> NodeKind;

    /// Number of nodes `n` (degrees of freedom): `V` for P1, `E` for Crouzeix–Raviart.
    fn dimension(&self) -> usize;

    /// Diagonal of the lumped mass matrix (`n` entries, units of area: the **integrated** weight
    /// of each node, `∫ f ≈ Σ_i mass_i f_i`). Zero only for a node no face uses.
    fn mass(&self) -> &[f64];

    /// The mass matrix the complex uses for this space (`n × n`, area), named `what` in errors:
    /// by default the lumped diagonal [`FunctionSpace::mass`] (an error if it is not positive on
    /// a node some face uses). A space with a consistent (Galerkin) mass `∫ ψ_i ψ_j` returns it
    /// here as a sparse matrix ([`Mass::sparse`]).
    fn mass_matrix(&self, what: &'static str) -> Result<Mass, DiscretizationError> {
        Mass::diagonal_positive_on_used_nodes(what, self.mass().to_vec(), self.node_components())
    }

    /// Gradient matrix `2F × n` (units 1/length): column `i` holds the gradient of basis
    /// function `i`, one tangent vector per face in that face's frame, rows `2t, 2t+1` for face
    /// `t`. The result is a **pointwise** face field.
    fn gradient(&self) -> &CsMat<f64>;

    /// The nodes whose basis functions are non-zero on face `face`, with their values at the point
    /// with barycentric coordinates `barycentric` (w.r.t. the face's corners `i0, i1, i2`). The
    /// weights sum to 1 and reproduce linear functions. Panics if `face` is out of range.
    fn interpolation_weights(&self, face: usize, barycentric: [f64; 3]) -> Vec<(usize, f64)>;

    /// Position of every node in space (`n` entries): vertices for P1, edge midpoints for CR.
    fn node_positions(&self) -> Vec<[f64; 3]>;

    /// Connected component of every node (`n` entries, in `0..component_count()`), or
    /// [`tvf_core::discretization::NO_COMPONENT`] for a node no face uses. The indicator function of
    /// each component spans the kernel of [`FunctionSpace::gradient`]: the Poisson solves fix one
    /// node per component.
    fn node_components(&self) -> &[usize];

    /// Number of connected components of the mesh.
    fn component_count(&self) -> usize;
}
