//! The [`HodgeComplex`] trait: the five matrices of a discrete Hodge decomposition, the single
//! source of truth of everything downstream.

use super::{
    ComplexParts, ComplexTopology, FieldRotation, FieldSampling, Mass, MatrixHash, NodeSpace,
    OperatorCache, PointEvaluation,
};
use crate::intrinsic::IntrinsicTriangulation;
use sprs::CsMat;

/// A discrete Hodge decomposition given as a short cochain complex with masses
///
/// ```text
/// potentials (n0) --d0--> fields (n1) --d1--> co-potentials (n2),   d1 · d0 = 0
///      M0                    M1                  M2 (acts on d1's integrated output)
/// ```
///
/// | entry | potentials | fields | co-potentials | `d0` | `d1` | `M0` | `M1` | `M2` |
/// |---|---|---|---|---|---|---|---|---|
/// | conforming | P1 (`V`) | face vectors (`2F`) | CR (`E`) | `G` | `G*ᵀ J M_X` | `M` | `M_X` | `M*⁻¹` |
/// | nonconforming | CR (`E`) | face vectors (`2F`) | P1 (`V`) | `G*` | `Gᵀ J M_X` | `M*` | `M_X` | `M⁻¹` |
/// | DEC 1-forms | vertices (`V`) | edges (`E`) | faces (`F`) | incidence | incidence | `⋆0` | `⋆1` | `⋆2` |
///
/// Potentials and fields are **pointwise** (nodal values, vector coefficients, or for DEC the
/// integrals the forms are defined by); `d0` is the gradient, `d1 x` the **integrated** curl in
/// the co-potential space (`M2 d1` the pointwise one). Every other operator — divergence and
/// curl, stiffness matrices, `S`, `L`, `B`, both scalar eigenproblems, eigenfields, the Hodge
/// decomposition — is derived from these five in [`super::HodgeOperators`] and nowhere else.
///
/// An implementor gives its [`ComplexParts`] (built and shape-checked once) and the
/// capabilities it offers; the accessors are provided from the parts and are not meant to be
/// overridden. The trait is object safe: the catalog of `tvf-discretizations` hands out
/// `Box<dyn HodgeComplex>`. Derived operators are cached in the parts' [`OperatorCache`] (a
/// wrapper that changes a matrix builds new parts, which come with a fresh cache).
pub trait HodgeComplex: Send + Sync {
    /// The five matrices, the nodes, the topology, the id and the operator cache: the one
    /// required method (together with the capabilities below, which default to none).
    fn parts(&self) -> &ComplexParts;

    /// Stable identifier, lower-case kebab-case (`conforming-barycentric`, `dec-circumcentric`):
    /// the catalog id, written into basis files and cache names.
    fn id(&self) -> &str {
        self.parts().id()
    }

    /// `d0` (`n1 × n0`): the gradient, potentials → fields.
    fn d0(&self) -> &CsMat<f64> {
        self.parts().d0()
    }

    /// `d1` (`n2 × n1`): the integrated curl, fields → co-potentials. `d1 · d0 = 0` up to
    /// round-off (on a mesh with boundary thanks to the boundary condition: the Dirichlet nodes'
    /// column of `d0` or row of `d1` is zero, see [`super::NodeSpace`]).
    fn d1(&self) -> &CsMat<f64> {
        self.parts().d1()
    }

    /// `M0` (`n0 × n0`, area): the inner product of potentials.
    fn m0(&self) -> &Mass {
        self.parts().m0()
    }

    /// `M1` (`n1 × n1`): the inner product of fields, `xᵀ M1 y = ∫ ⟨x, y⟩`.
    fn m1(&self) -> &Mass {
        self.parts().m1()
    }

    /// `M2` (`n2 × n2`, 1/area): turns `d1`'s integrated values into pointwise ones; `M2⁻¹` is the
    /// inner product of co-potentials. Stored as `M2⁻¹` ([`super::MassForm::Inverse`]) when that
    /// is the sparse one (a consistent co-potential mass).
    fn m2(&self) -> &Mass {
        self.parts().m2()
    }

    /// The nodes of the potential space (`n0`).
    fn potential_nodes(&self) -> &NodeSpace {
        self.parts().potential_nodes()
    }

    /// The nodes of the field space (`n1`).
    fn field_nodes(&self) -> &NodeSpace {
        self.parts().field_nodes()
    }

    /// The nodes of the co-potential space (`n2`).
    fn co_potential_nodes(&self) -> &NodeSpace {
        self.parts().co_potential_nodes()
    }

    /// Components, harmonic dimension, boundary and boundary condition of the complex.
    fn topology(&self) -> &ComplexTopology {
        self.parts().topology()
    }

    /// The hashes of the five matrices and the fixed nodes, computed once per complex: what
    /// basis files and cached bases are keyed on besides the id and the mesh.
    fn matrix_hash(&self) -> MatrixHash {
        self.parts().matrix_hash()
    }

    /// Storage for the derived operators of [`super::HodgeOperators`] (computed once, on first
    /// use).
    fn operator_cache(&self) -> &OperatorCache {
        self.parts().operator_cache()
    }

    /// Sampling fields as 3D vectors at points, if the discretization offers it.
    fn sampling(&self) -> Option<&dyn FieldSampling> {
        None
    }

    /// The rotation `J` of fields by +π/2, if the field space has one.
    fn rotation(&self) -> Option<&dyn FieldRotation> {
        None
    }

    /// Evaluation of potentials and co-potentials at points, if the discretization offers it.
    fn point_evaluation(&self) -> Option<&dyn PointEvaluation> {
        None
    }

    /// The intrinsic triangulation the complex was built on, if it was built on one (a catalog
    /// entry with the intrinsic Delaunay modifier): its vertices, edges and faces are the nodes
    /// of the complex's spaces, while sampling, point evaluation and field files speak of the
    /// input mesh's faces.
    fn intrinsic_triangulation(&self) -> Option<&IntrinsicTriangulation> {
        None
    }
}
