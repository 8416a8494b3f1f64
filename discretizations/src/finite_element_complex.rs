//! [`FiniteElementComplex`]: a Hodge complex built from a potential space and a co-potential space
//! over the face fields; [`Conforming`] and [`Nonconforming`] are its two instances from the paper.

use crate::face_geometry::FaceGeometry;
use crate::{CrouzeixRaviart, FaceFields, FunctionSpace, LagrangeP1, MassLumping};
use sprs::CsMat;
use tvf_core::discretization::sparse::{product, reciprocal, scale_cols, transpose};
use tvf_core::discretization::{
    ComplexTopology, DiagonalMass, DiscretizationError, FieldRotation, FieldSampling, HodgeComplex,
    NodeKind, NodeSpace, OperatorCache, PointEvaluation,
};
use tvf_core::SurfaceMesh;

/// The Hodge complex `P --d0--> X_h --d1--> Q` of two function spaces over the face fields:
/// `d0 = G_P`, `d1 = G_Qᵀ J M_X`, `M0 = mass(P)`, `M1 = M_X`, `M2 = mass(Q)⁻¹`.
///
/// Any pair of [`FunctionSpace`]s makes a complex with [`FiniteElementComplex::from_spaces`]. It
/// offers every capability: sampling (exact, one vector per face), the rotation `J` and point
/// evaluation (the spaces' interpolation weights).
#[derive(Debug, Clone)]
pub struct FiniteElementComplex<P, Q> {
    id: String,
    potentials: P,
    co_potentials: Q,
    fields: FaceFields,
    d1: CsMat<f64>,
    m0: DiagonalMass,
    m1: DiagonalMass,
    m2: DiagonalMass,
    potential_nodes: NodeSpace,
    field_nodes: NodeSpace,
    co_potential_nodes: NodeSpace,
    topology: ComplexTopology,
    cache: OperatorCache,
}

/// The conforming decomposition `X_h = grad S_h ⊕ J grad S*_h ⊕ H_h` (the paper's choice):
/// potentials P1 (`V`), co-potentials Crouzeix–Raviart (`E`).
pub type Conforming = FiniteElementComplex<LagrangeP1, CrouzeixRaviart>;

/// The nonconforming decomposition `X_h = grad S*_h ⊕ J grad S_h ⊕ H*_h`:
/// potentials Crouzeix–Raviart (`E`), co-potentials P1 (`V`).
pub type Nonconforming = FiniteElementComplex<CrouzeixRaviart, LagrangeP1>;

/// The topology of `mesh` as a complex sees it: components, `2g` summed over the components,
/// boundary.
pub fn mesh_topology(mesh: &SurfaceMesh) -> ComplexTopology {
    ComplexTopology {
        component_count: mesh.component_count(),
        harmonic_dimension: 2 * mesh.genus(),
        has_boundary: !mesh.is_closed(),
    }
}

/// The nodes of a function space.
fn function_nodes(space: &impl FunctionSpace) -> NodeSpace {
    NodeSpace {
        kind: space.node_kind(),
        positions: space.node_positions(),
        components: space.node_components().to_vec(),
    }
}

/// The `2F` field nodes: two per face, at its centroid.
fn face_frame_nodes(mesh: &SurfaceMesh) -> NodeSpace {
    let centroid = |f: &[usize; 3]| {
        let p = f.map(|i| mesh.positions()[i]);
        std::array::from_fn(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0)
    };
    NodeSpace {
        kind: NodeKind::FaceFrames,
        positions: mesh.faces().iter().flat_map(|f| [centroid(f); 2]).collect(),
        components: mesh
            .face_components()
            .iter()
            .flat_map(|&c| [c, c])
            .collect(),
    }
}

impl<P: FunctionSpace, Q: FunctionSpace> FiniteElementComplex<P, Q> {
    /// Assembles the complex from its spaces (`d1 = G_Qᵀ J M_X`, `M2 = mass(Q)⁻¹`) with catalog id
    /// `id`. Fails if a gradient does not have `2F` rows or a mass is not positive on the nodes
    /// faces use.
    pub fn from_spaces(
        id: impl Into<String>,
        mesh: &SurfaceMesh,
        potentials: P,
        co_potentials: Q,
        fields: FaceFields,
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
        let d1 = product(&transpose(co_potentials.gradient()), &rotated_mass);
        let potential_nodes = function_nodes(&potentials);
        let co_potential_nodes = function_nodes(&co_potentials);
        let field_nodes = face_frame_nodes(mesh);
        let m0 = DiagonalMass::positive_on_used_nodes(
            "M0 (potential mass)",
            potentials.mass().to_vec(),
            &potential_nodes.components,
        )?;
        let m1 = DiagonalMass::positive_on_used_nodes(
            "M1 (field mass)",
            fields.mass().to_vec(),
            &field_nodes.components,
        )?;
        DiagonalMass::positive_on_used_nodes(
            "co-potential mass",
            co_potentials.mass().to_vec(),
            &co_potential_nodes.components,
        )?;
        let m2 = DiagonalMass::new(
            "M2 (inverse co-potential mass)",
            reciprocal(co_potentials.mass()),
        )?;
        Ok(Self {
            id: id.into(),
            potentials,
            co_potentials,
            fields,
            d1,
            m0,
            m1,
            m2,
            potential_nodes,
            field_nodes,
            co_potential_nodes,
            topology: mesh_topology(mesh),
            cache: OperatorCache::default(),
        })
    }

    /// The potential space.
    pub fn potential_space(&self) -> &P {
        &self.potentials
    }

    /// The co-potential space.
    pub fn co_potential_space(&self) -> &Q {
        &self.co_potentials
    }

    /// The face fields.
    pub fn face_fields(&self) -> &FaceFields {
        &self.fields
    }
}

impl Conforming {
    /// The conforming complex of `mesh` with the given mass lumping (for both function spaces),
    /// catalog id `conforming-{lumping}`. Fails on a degenerate face.
    pub fn new(mesh: &SurfaceMesh, lumping: MassLumping) -> Result<Self, DiscretizationError> {
        let geometry = FaceGeometry::new(mesh)?;
        Self::from_spaces(
            format!("conforming-{}", lumping.name()),
            mesh,
            LagrangeP1::from_geometry(mesh, &geometry, lumping),
            CrouzeixRaviart::from_geometry(mesh, &geometry, lumping),
            FaceFields::from_geometry(&geometry),
        )
    }
}

impl Nonconforming {
    /// The nonconforming complex of `mesh` with the given mass lumping (for both function
    /// spaces), catalog id `nonconforming-{lumping}`. Fails on a degenerate face.
    pub fn new(mesh: &SurfaceMesh, lumping: MassLumping) -> Result<Self, DiscretizationError> {
        let geometry = FaceGeometry::new(mesh)?;
        Self::from_spaces(
            format!("nonconforming-{}", lumping.name()),
            mesh,
            CrouzeixRaviart::from_geometry(mesh, &geometry, lumping),
            LagrangeP1::from_geometry(mesh, &geometry, lumping),
            FaceFields::from_geometry(&geometry),
        )
    }
}

impl<P, Q> HodgeComplex for FiniteElementComplex<P, Q>
where
    P: FunctionSpace + Send + Sync,
    Q: FunctionSpace + Send + Sync,
{
    fn id(&self) -> &str {
        &self.id
    }

    fn d0(&self) -> &CsMat<f64> {
        self.potentials.gradient()
    }

    fn d1(&self) -> &CsMat<f64> {
        &self.d1
    }

    fn m0(&self) -> &DiagonalMass {
        &self.m0
    }

    fn m1(&self) -> &DiagonalMass {
        &self.m1
    }

    fn m2(&self) -> &DiagonalMass {
        &self.m2
    }

    fn potential_nodes(&self) -> &NodeSpace {
        &self.potential_nodes
    }

    fn field_nodes(&self) -> &NodeSpace {
        &self.field_nodes
    }

    fn co_potential_nodes(&self) -> &NodeSpace {
        &self.co_potential_nodes
    }

    fn topology(&self) -> &ComplexTopology {
        &self.topology
    }

    fn operator_cache(&self) -> &OperatorCache {
        &self.cache
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
    fn potential_weights(&self, face: usize, barycentric: [f64; 3]) -> Vec<(usize, f64)> {
        self.potentials.interpolation_weights(face, barycentric)
    }

    fn co_potential_weights(&self, face: usize, barycentric: [f64; 3]) -> Vec<(usize, f64)> {
        self.co_potentials.interpolation_weights(face, barycentric)
    }
}
