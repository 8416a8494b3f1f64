//! [`FiniteElementComplex`]: a Hodge complex built from a potential space and a co-potential space
//! over the face fields; [`Conforming`] and [`Nonconforming`] are its two instances from the paper.

use crate::boundary_conditions::{drop_columns, drop_rows, mesh_topology, with_dirichlet_boundary};
use crate::{CrouzeixRaviart, FaceFields, FunctionSpace, LagrangeP1};
use tvf_core::discretization::sparse::{product, reciprocal, scale_cols, transpose};
use tvf_core::discretization::{
    BoundaryCondition, ComplexParts, DiscretizationError, FieldRotation, FieldSampling,
    HodgeComplex, Mass, MassForm, MassStorage, NodeKind, NodeSpace, PointEvaluation,
};
use tvf_core::{SurfacePoint, TriangleMesh};

/// The Hodge complex `P --d0--> X_h --d1--> Q` of two function spaces over the face fields:
/// `d0 = G_P`, `d1 = G_Qᵀ J M_X`, `M0 = mass(P)`, `M1 = M_X`, `M2 = mass(Q)⁻¹`, with each
/// space's [`FunctionSpace::mass_matrix`] (lumped, or consistent).
///
/// Any pair of [`FunctionSpace`]s makes a complex with [`FiniteElementComplex::from_spaces`]. It
/// offers every capability: sampling (exact, one vector per face), the rotation `J` and point
/// evaluation (the spaces' interpolation weights).
#[derive(Debug, Clone)]
pub struct FiniteElementComplex<P, Q> {
    parts: ComplexParts,
    potentials: P,
    co_potentials: Q,
    fields: FaceFields,
}

/// The conforming decomposition `X_h = grad S_h ⊕ J grad S*_h ⊕ H_h` (the paper's choice):
/// potentials P1 (`V`), co-potentials Crouzeix–Raviart (`E`). On a mesh with boundary
/// `X_h = ∇S_h ⊕ J∇S*_h,0 ⊕ H_N` (tangential) or `X_h = ∇S_h,0 ⊕ J∇S*_h ⊕ H_D` (normal). Its
/// consistent variant has `M0` the consistent P1 mass `Σ_T |T| (1 + δ_ij)/12` (sparse) and the
/// Crouzeix–Raviart mass `|T|/3` per face and edge, which is already the consistent one (the
/// Crouzeix–Raviart basis is `L²`-orthogonal): on a closed mesh the spectrum of `L` is
/// `eig(cotan, consistent P1 mass) ∪ eig(CR stiffness, CR mass)`. Constructors:
/// [`FiniteElementComplex::new`] and its siblings (`crate::paper_complexes`).
pub type Conforming = FiniteElementComplex<LagrangeP1, CrouzeixRaviart>;

/// The nonconforming decomposition `X_h = grad S*_h ⊕ J grad S_h ⊕ H*_h`:
/// potentials Crouzeix–Raviart (`E`), co-potentials P1 (`V`). On a mesh with boundary
/// `X_h = ∇S*_h ⊕ J∇S_h,0 ⊕ H*_N` (tangential) or `X_h = ∇S*_h,0 ⊕ J∇S_h ⊕ H*_D` (normal). Its
/// consistent variant has the consistent P1 mass as the co-potential inner product: `M2` is
/// its inverse, dense, so it is stored as the sparse `M2⁻¹` ([`Mass::sparse_inverse`]); the
/// Crouzeix–Raviart potential mass `M0` is diagonal and already consistent. Same spectrum as
/// the consistent [`Conforming`] on a closed mesh. Constructors: [`FiniteElementComplex::new`]
/// and its siblings.
pub type Nonconforming = FiniteElementComplex<CrouzeixRaviart, LagrangeP1>;

/// The nodes of a function space (free boundary values).
fn function_nodes(space: &impl FunctionSpace) -> NodeSpace {
    NodeSpace::with_constant_kernel(
        space.node_kind(),
        space.node_positions(),
        space.node_components().to_vec(),
        space.component_count(),
    )
}

/// The `2F` field nodes: two per face, at its centroid.
fn face_frame_nodes(mesh: &TriangleMesh) -> NodeSpace {
    let centroid = |f: &[usize; 3]| {
        let p = f.map(|i| mesh.positions()[i]);
        std::array::from_fn(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0)
    };
    NodeSpace::with_constant_kernel(
        NodeKind::FaceFrames,
        mesh.faces().iter().flat_map(|f| [centroid(f); 2]).collect(),
        mesh.face_components()
            .iter()
            .flat_map(|&c| [c, c])
            .collect(),
        mesh.component_count(),
    )
}

impl<P: FunctionSpace, Q: FunctionSpace> FiniteElementComplex<P, Q> {
    /// Assembles the complex from its spaces (`d0 = G_P`, `d1 = G_Qᵀ J M_X`, `M2 = mass(Q)⁻¹`)
    /// with catalog id `id` and, on a mesh with boundary, the default boundary condition
    /// ([`BoundaryCondition::Tangential`]). See [`FiniteElementComplex::from_spaces_with_boundary`].
    pub fn from_spaces(
        id: impl Into<String>,
        mesh: &TriangleMesh,
        potentials: P,
        co_potentials: Q,
        fields: FaceFields,
    ) -> Result<Self, DiscretizationError> {
        Self::from_spaces_with_boundary(
            id,
            mesh,
            potentials,
            co_potentials,
            fields,
            BoundaryCondition::default(),
        )
    }

    /// Assembles the complex from its spaces with boundary condition `boundary`. On a mesh with
    /// boundary, [`BoundaryCondition::Tangential`] fixes the co-potentials at their boundary nodes
    /// to zero (drops those rows of `d1`: `S*_h,0` for the conforming complex) and
    /// [`BoundaryCondition::Normal`] fixes the potentials there (drops those columns of `d0`:
    /// `S_h,0`); either way `d1 · d0 = 0`. The masses are assembled over every node
    /// ([`FunctionSpace::mass_matrix`]; `M2` is the inverse of the co-potential space's, stored
    /// as `M2⁻¹` when that is the sparse one) and the seam restricts them to the free nodes. Fails
    /// if a gradient does not have `2F` rows or a mass is not positive definite on the free nodes.
    pub fn from_spaces_with_boundary(
        id: impl Into<String>,
        mesh: &TriangleMesh,
        potentials: P,
        co_potentials: Q,
        fields: FaceFields,
        boundary: BoundaryCondition,
    ) -> Result<Self, DiscretizationError> {
        for gradient in [potentials.gradient(), co_potentials.gradient()] {
            if gradient.rows() != fields.field_dimension() {
                return Err(DiscretizationError::DimensionMismatch {
                    what: "gradient rows (must equal the field dimension 2F)",
                    expected: fields.field_dimension(),
                    found: gradient.rows(),
                });
            }
        }
        let rotated_mass = scale_cols(fields.rotation(), fields.mass());
        let mut d0 = potentials.gradient().clone();
        let mut d1 = product(&transpose(co_potentials.gradient()), &rotated_mass);
        let mut potential_nodes = function_nodes(&potentials);
        let mut co_potential_nodes = function_nodes(&co_potentials);
        if !mesh.is_closed() {
            match boundary {
                BoundaryCondition::Tangential => {
                    co_potential_nodes = with_dirichlet_boundary(co_potential_nodes, mesh);
                    d1 = drop_rows(&d1, &co_potential_nodes.dirichlet);
                }
                BoundaryCondition::Normal => {
                    potential_nodes = with_dirichlet_boundary(potential_nodes, mesh);
                    d0 = drop_columns(&d0, &potential_nodes.dirichlet);
                }
            }
        }
        let field_nodes = face_frame_nodes(mesh);
        let m0 = potentials.mass_matrix("M0 (potential mass)")?;
        let m1 = Mass::diagonal_positive_on_used_nodes(
            "M1 (field mass)",
            fields.mass().to_vec(),
            &field_nodes.components,
        )?;
        let m2 = inverse_co_potential_mass(co_potentials.mass_matrix("co-potential mass")?)?;
        Ok(Self {
            parts: ComplexParts::new(
                id,
                d0,
                d1,
                [m0, m1, m2],
                [potential_nodes, field_nodes, co_potential_nodes],
                mesh_topology(mesh, boundary),
            )?,
            potentials,
            co_potentials,
            fields,
        })
    }

    /// The face fields.
    pub fn face_fields(&self) -> &FaceFields {
        &self.fields
    }
}

/// `M2`, the inverse of the co-potential space's mass matrix `mass`, in the form in which it is
/// sparse: the reciprocal of a lumped diagonal, or a consistent mass stored as `M2⁻¹`
/// ([`Mass::sparse_inverse`]).
pub(crate) fn inverse_co_potential_mass(mass: Mass) -> Result<Mass, DiscretizationError> {
    match (mass.storage(), mass.form()) {
        (MassStorage::Diagonal(values), _) => {
            Mass::diagonal("M2 (inverse co-potential mass)", reciprocal(values))
        }
        (MassStorage::Sparse(matrix), MassForm::Direct) => Mass::sparse_inverse(
            "M2 (inverse of the consistent co-potential mass)",
            matrix.clone(),
        ),
        (MassStorage::Sparse(matrix), MassForm::Inverse) => {
            Mass::sparse("M2 (inverse co-potential mass)", matrix.clone())
        }
    }
}

impl<P, Q> HodgeComplex for FiniteElementComplex<P, Q>
where
    P: FunctionSpace + Send + Sync,
    Q: FunctionSpace + Send + Sync,
{
    fn parts(&self) -> &ComplexParts {
        &self.parts
    }

    fn sampling(&self) -> Option<&dyn FieldSampling> {
        Some(&self.fields)
    }

    fn rotation(&self) -> Option<&dyn FieldRotation> {
        Some(&self.fields)
    }

    fn point_evaluation(&self) -> Option<&dyn PointEvaluation> {
        Some(self)
    }
}

impl<P, Q> PointEvaluation for FiniteElementComplex<P, Q>
where
    P: FunctionSpace + Send + Sync,
    Q: FunctionSpace + Send + Sync,
{
    fn potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        self.potentials
            .interpolation_weights(point.face, point.triangle_coordinates())
    }

    fn co_potential_weights(&self, point: &SurfacePoint) -> Vec<(usize, f64)> {
        self.co_potentials
            .interpolation_weights(point.face, point.triangle_coordinates())
    }
}
