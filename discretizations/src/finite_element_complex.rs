//! [`FiniteElementComplex`]: a Hodge complex built from a potential space, a co-potential space and
//! a field space; [`Conforming`] and [`Nonconforming`] are its two instances from the paper.

use crate::face_geometry::FaceGeometry;
use crate::{CrouzeixRaviart, FaceFields, LagrangeP1, MassLumping};
use sprs::CsMat;
use tvf_core::discretization::sparse::{product, reciprocal, scale_cols, transpose};
use tvf_core::discretization::{DiscretizationError, FieldSpace, FunctionSpace, HodgeComplex};
use tvf_core::SurfaceMesh;

/// The Hodge complex `P --d0--> X --d1--> Q` of two function spaces over a field space:
/// `d0 = G_P`, `d1 = G_Qᵀ J M_X`, `M0 = mass(P)`, `M1 = M_X`, `M2 = mass(Q)⁻¹`.
///
/// Any pair of [`FunctionSpace`]s whose gradients land in the same [`FieldSpace`] makes a complex
/// with [`FiniteElementComplex::from_spaces`]; every operator then comes from
/// [`tvf_core::discretization::HodgeOperators`].
#[derive(Debug, Clone)]
pub struct FiniteElementComplex<P, Q, X = FaceFields> {
    name: String,
    potentials: P,
    co_potentials: Q,
    fields: X,
    d1: CsMat<f64>,
    m2: Vec<f64>,
    harmonic_dimension: usize,
    has_boundary: bool,
}

/// The conforming decomposition `X_h = grad S_h ⊕ J grad S*_h ⊕ H_h` (the paper's choice):
/// potentials P1 (`V`), co-potentials Crouzeix–Raviart (`E`).
pub type Conforming = FiniteElementComplex<LagrangeP1, CrouzeixRaviart>;

/// The nonconforming decomposition `X_h = grad S*_h ⊕ J grad S_h ⊕ H*_h`:
/// potentials Crouzeix–Raviart (`E`), co-potentials P1 (`V`).
pub type Nonconforming = FiniteElementComplex<CrouzeixRaviart, LagrangeP1>;

/// Facts about the mesh a complex needs besides its spaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Topology {
    /// `2g` summed over the components (the harmonic dimension on a closed mesh).
    pub harmonic_dimension: usize,
    /// Whether the mesh has boundary edges.
    pub has_boundary: bool,
}

impl Topology {
    /// Reads the topology of `mesh`.
    pub fn of(mesh: &SurfaceMesh) -> Self {
        Self {
            harmonic_dimension: 2 * mesh.genus(),
            has_boundary: !mesh.is_closed(),
        }
    }
}

impl<P: FunctionSpace, Q: FunctionSpace, X: FieldSpace> FiniteElementComplex<P, Q, X> {
    /// Assembles the complex from its three spaces (`d1 = G_Qᵀ J M_X`, `M2 = mass(Q)⁻¹`).
    ///
    /// Fails with [`DiscretizationError::DimensionMismatch`] if a gradient does not have `2F` rows.
    pub fn from_spaces(
        name: impl Into<String>,
        potentials: P,
        co_potentials: Q,
        fields: X,
        topology: Topology,
    ) -> Result<Self, DiscretizationError> {
        for gradient in [potentials.gradient(), co_potentials.gradient()] {
            if gradient.rows() != fields.dimension() {
                return Err(DiscretizationError::DimensionMismatch {
                    what: "gradient rows (must equal the field dimension 2F)",
                    expected: fields.dimension(),
                    found: gradient.rows(),
                });
            }
        }
        let rotated_mass = scale_cols(fields.rotation(), fields.mass());
        let d1 = product(&transpose(co_potentials.gradient()), &rotated_mass);
        let m2 = reciprocal(co_potentials.mass());
        Ok(Self {
            name: name.into(),
            potentials,
            co_potentials,
            fields,
            d1,
            m2,
            harmonic_dimension: topology.harmonic_dimension,
            has_boundary: topology.has_boundary,
        })
    }
}

impl Conforming {
    /// The conforming complex of `mesh` with the given mass lumping (for both function spaces).
    /// Fails on a degenerate face.
    pub fn new(mesh: &SurfaceMesh, lumping: MassLumping) -> Result<Self, DiscretizationError> {
        let geometry = FaceGeometry::new(mesh)?;
        Self::from_spaces(
            format!("conforming ({})", lumping.name()),
            LagrangeP1::from_geometry(mesh, &geometry, lumping),
            CrouzeixRaviart::from_geometry(mesh, &geometry, lumping),
            FaceFields::from_geometry(mesh, &geometry),
            Topology::of(mesh),
        )
    }
}

impl Nonconforming {
    /// The nonconforming complex of `mesh` with the given mass lumping (for both function spaces).
    /// Fails on a degenerate face.
    pub fn new(mesh: &SurfaceMesh, lumping: MassLumping) -> Result<Self, DiscretizationError> {
        let geometry = FaceGeometry::new(mesh)?;
        Self::from_spaces(
            format!("nonconforming ({})", lumping.name()),
            CrouzeixRaviart::from_geometry(mesh, &geometry, lumping),
            LagrangeP1::from_geometry(mesh, &geometry, lumping),
            FaceFields::from_geometry(mesh, &geometry),
            Topology::of(mesh),
        )
    }
}

impl<P: FunctionSpace, Q: FunctionSpace, X: FieldSpace> HodgeComplex
    for FiniteElementComplex<P, Q, X>
{
    type Potentials = P;
    type CoPotentials = Q;
    type Fields = X;

    fn name(&self) -> String {
        self.name.clone()
    }

    fn potentials(&self) -> &P {
        &self.potentials
    }

    fn co_potentials(&self) -> &Q {
        &self.co_potentials
    }

    fn fields(&self) -> &X {
        &self.fields
    }

    fn d1(&self) -> &CsMat<f64> {
        &self.d1
    }

    fn m2(&self) -> &[f64] {
        &self.m2
    }

    fn harmonic_dimension(&self) -> usize {
        self.harmonic_dimension
    }

    fn has_boundary(&self) -> bool {
        self.has_boundary
    }
}
