//! The [`HodgeComplex`] trait: the short cochain complex behind a discrete Hodge decomposition.

use super::{FieldSpace, FunctionSpace};
use sprs::CsMat;

/// A discrete Hodge decomposition `X_h = d0(potentials) ⊕ M1⁻¹d1ᵀ(co-potentials) ⊕ H`, given as
/// the cochain complex
///
/// ```text
/// potentials (n0) --d0--> fields (2F) --d1--> co-potentials (n2),   d1 · d0 = 0
/// ```
///
/// with diagonal masses `M0` (potentials), `M1` (fields) and `M2` (acting on the integrated
/// output of `d1`). The two instances of the paper:
///
/// | complex | potentials | co-potentials | `d0` | `d1` | `M0` | `M1` | `M2` |
/// |---|---|---|---|---|---|---|---|
/// | conforming | P1 (`V`) | CR (`E`) | `G` | `G*ᵀ J M_X` | `M` | `M_X` | `M*⁻¹` |
/// | nonconforming | CR (`E`) | P1 (`V`) | `G*` | `Gᵀ J M_X` | `M*` | `M_X` | `M⁻¹` |
///
/// Potentials and co-potentials are **pointwise** nodal values of their function spaces;
/// `d0 f` is a pointwise field (the gradient), `d1 v` is the **integrated** curl of `v` in the
/// co-potential space (`M2 d1` is the pointwise one). Everything derived from these five things
/// lives in the blanket extension [`crate::discretization::HodgeOperators`].
///
/// Implementors provide the spaces, `d1`, `M2` and the harmonic dimension; `d0`, `M0`, `M1`
/// default to the potential gradient and the spaces' masses.
pub trait HodgeComplex {
    /// The potential space (the source of `d0`).
    type Potentials: FunctionSpace;
    /// The co-potential space (the target of `d1`).
    type CoPotentials: FunctionSpace;
    /// The field space.
    type Fields: FieldSpace;

    /// Short human-readable name, e.g. `"conforming (barycentric)"`.
    fn name(&self) -> String;

    /// The potential space `S_h` (conforming) or `S*_h` (nonconforming).
    fn potentials(&self) -> &Self::Potentials;

    /// The co-potential space `S*_h` (conforming) or `S_h` (nonconforming).
    fn co_potentials(&self) -> &Self::CoPotentials;

    /// The field space `X_h`.
    fn fields(&self) -> &Self::Fields;

    /// `d0` (`2F × n0`): the gradient of the potential space (pointwise in, pointwise out,
    /// units 1/length).
    fn d0(&self) -> &CsMat<f64> {
        self.potentials().gradient()
    }

    /// `d1` (`n2 × 2F`): the integrated curl into the co-potential space,
    /// `d1 = G_coᵀ J M1` with `G_co` the co-potential gradient (units length). `d1 · d0 = 0` up to
    /// round-off on closed meshes.
    fn d1(&self) -> &CsMat<f64>;

    /// Diagonal of `M0` (`n0` entries, area): the lumped mass of the potential space.
    fn m0(&self) -> &[f64] {
        self.potentials().mass()
    }

    /// Diagonal of `M1 = M_X` (`2F` entries, area).
    fn m1(&self) -> &[f64] {
        self.fields().mass()
    }

    /// Diagonal of `M2` (`n2` entries, 1/area): the inverse lumped mass of the co-potential space
    /// (zero for a node no face uses). It turns `d1`'s integrated values into pointwise ones.
    fn m2(&self) -> &[f64];

    /// Dimension of the harmonic space `H`: `2g` summed over the components of a closed mesh.
    fn harmonic_dimension(&self) -> usize;

    /// Whether the mesh has boundary edges. Then `d1 · d0 ≠ 0` on the boundary (the operators are
    /// assembled with natural boundary conditions) and the Hodge decomposition is not defined.
    fn has_boundary(&self) -> bool;

    /// Number of connected components.
    fn component_count(&self) -> usize {
        self.potentials().component_count()
    }
}
