//! [`PrimalFormComplex`]: a complex of primal forms ([`PrimalForms`]) with its three masses,
//! Whitney sampling and point evaluation (a [`SampledComplex`]) — the one type behind
//! [`crate::DecComplex`] and [`crate::WhitneyGalerkin`], which differ only in the masses (the
//! marker `M`). A crate of your own makes a DEC-like discretization the same way: a marker type of
//! its own and [`PrimalFormComplex::assemble`] with its masses (the example crate
//! `own-discretization` does, with a Hodge star of its own).

use crate::face_geometry::FaceGeometry;
use crate::primal_forms::{PrimalFormEvaluation, PrimalForms};
use crate::sampled_complex::SampledComplex;
use crate::whitney_sampling::WhitneySampling;
use tvf_core::discretization::{BoundaryCondition, DiscretizationError, Mass, NodeSpace};
use tvf_core::TriangleMesh;

/// The complex `0-forms (V) --d0--> 1-forms (E) --d1--> 2-forms (F)` of [`PrimalForms`] with
/// masses chosen by the marker `M` ([`crate::HodgeStars`] for DEC, [`crate::GalerkinMasses`]
/// for Whitney forms), sampled by Whitney interpolation ([`WhitneySampling`]); 0-forms are
/// evaluated linearly ([`PrimalFormEvaluation`]), 2-forms constant per face. There is no rotation
/// `J` on 1-forms.
pub type PrimalFormComplex<M> = SampledComplex<WhitneySampling, PrimalFormEvaluation, M>;

impl<M> PrimalFormComplex<M> {
    /// Assembles the complex of `mesh` (face geometry `geometry`, [`FaceGeometry::new`]) with
    /// boundary condition `boundary` and catalog id `id` (`+{boundary}` appended on a mesh with
    /// boundary); `masses` gives `[M0, M1, M2]` (`V × V`, `E × E`, `F × F`; see
    /// [`HodgeComplex`] for their units) from the node spaces of the 0-, 1- and 2-forms
    /// ([`PrimalForms::nodes`]: use their `components` for
    /// [`Mass::diagonal_positive_on_used_nodes`]). Fails with the masses' error, or when
    /// [`PrimalForms::into_parts`] refuses the parts (shapes, `d1 d0 ≠ 0`).
    pub fn assemble(
        id: &str,
        mesh: &TriangleMesh,
        geometry: &FaceGeometry,
        boundary: BoundaryCondition,
        masses: impl FnOnce(&[NodeSpace; 3]) -> Result<[Mass; 3], DiscretizationError>,
    ) -> Result<Self, DiscretizationError> {
        let forms = PrimalForms::new(mesh, boundary);
        let masses = masses(&forms.nodes)?;
        let sampling = WhitneySampling::new(mesh, geometry, forms.nodes[1].dirichlet.clone());
        let parts = forms.into_parts(id, mesh, boundary, masses)?;
        Ok(Self::from_parts(
            parts,
            sampling,
            PrimalFormEvaluation::new(mesh),
        ))
    }
}

/// `M2 = 1/area` per face (diagonal, `F` entries, 1/area), named `what` in errors: a 2-form is
/// stored by its integral, and `M2⁻¹ = |T|` is the `L²` mass of the piecewise constants.
/// `face_nodes` are the 2-forms' nodes ([`PrimalForms::nodes`]`[2]`).
pub fn inverse_face_areas(
    what: &'static str,
    geometry: &FaceGeometry,
    face_nodes: &NodeSpace,
) -> Result<Mass, DiscretizationError> {
    Mass::diagonal_positive_on_used_nodes(
        what,
        geometry.areas.iter().map(|a| 1.0 / a).collect(),
        &face_nodes.components,
    )
}
