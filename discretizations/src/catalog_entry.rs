//! [`CatalogEntry`]: one discretization of a [`crate::Catalog`] — its id, what it is, what it
//! needs of the mesh, the boundary conditions it offers, and a constructor that may carry
//! parameters (a closure).

use crate::complex_id::complex_id;
use crate::intrinsic_delaunay::{IntrinsicConstructor, IntrinsicInput};
use std::sync::Arc;
use tvf_core::discretization::{BoundaryCondition, DiscretizationError, HodgeComplex};
use tvf_core::mesh::Mesh;
use tvf_core::TriangleMesh;

/// A complex built by a catalog entry, behind the object-safe seam.
pub type BoxedComplex = Box<dyn HodgeComplex>;

/// What a catalog entry runs to build its complex: the mesh and the boundary condition in, the
/// complex out. A closure, so that an entry can carry parameters (a blend factor, a scale).
pub type EntryConstructor = Arc<
    dyn Fn(&dyn Mesh, BoundaryCondition) -> Result<BoxedComplex, DiscretizationError> + Send + Sync,
>;

/// What an entry needs of the mesh unless it says otherwise.
pub const ANY_MESH: &str = "none (any valid mesh without degenerate faces)";

/// One discretization: a stable id, a one-line description, what it needs of the mesh, the
/// boundary conditions it offers on meshes with boundary (and what each fixes), and its
/// constructor.
///
/// Made with [`CatalogEntry::new`] and the `with_…` methods; cheap to clone (the constructor is
/// shared).
///
/// ```
/// use tvf_core::discretization::BoundaryCondition;
/// use tvf_discretizations::{BoxedComplex, CatalogEntry, Conforming, MassLumping};
///
/// let entry = CatalogEntry::new(
///     "conforming-barycentric-again",
///     "the paper's conforming decomposition once more",
///     |mesh, boundary| -> Result<BoxedComplex, _> {
///         let complex = Conforming::with_boundary(mesh, MassLumping::Barycentric, boundary)?;
///         Ok(Box::new(complex))
///     },
/// )
/// .with_boundary_condition(BoundaryCondition::Tangential, "co-potentials zero on the boundary");
/// assert_eq!(entry.boundary_conditions(), [BoundaryCondition::Tangential]);
/// ```
#[derive(Clone)]
pub struct CatalogEntry {
    id: String,
    description: String,
    preconditions: String,
    needs_delaunay: bool,
    needs_triangles: bool,
    boundary_conditions: Vec<BoundaryCondition>,
    boundary_meanings: Vec<String>,
    constructor: EntryConstructor,
    intrinsic: Option<IntrinsicConstructor>,
}

impl CatalogEntry {
    /// An entry of a discretization of **triangle** meshes with id `id` (checked when it is
    /// added to a catalog: lower case, see [`crate::Catalog::add`]), a one-line `description`
    /// (potentials, fields, co-potentials and masses) and its `constructor`, which must give its
    /// complex the id [`complex_id`]`(id, mesh, boundary)` (checked by
    /// [`CatalogEntry::build_with`]). On a polygon mesh the entry refuses with
    /// [`DiscretizationError::NeedsTriangles`]. It needs nothing else of the mesh ([`ANY_MESH`])
    /// and offers no boundary condition (closed meshes only) until told otherwise.
    pub fn new<F>(id: impl Into<String>, description: impl Into<String>, constructor: F) -> Self
    where
        F: Fn(&TriangleMesh, BoundaryCondition) -> Result<BoxedComplex, DiscretizationError>
            + Send
            + Sync
            + 'static,
    {
        let id = id.into();
        let entry_id = id.clone();
        let mut entry = Self::on_any_mesh(id, description, move |mesh, boundary| {
            match mesh.as_triangles() {
                Some(triangles) => constructor(triangles, boundary),
                None => {
                    let faces = mesh.face_corners();
                    Err(DiscretizationError::NeedsTriangles {
                        discretization: entry_id.clone(),
                        polygons: (0..faces.face_count())
                            .filter(|&f| faces.corners(f).len() > 3)
                            .count(),
                    })
                }
            }
        });
        entry.needs_triangles = true;
        entry
    }

    /// Like [`CatalogEntry::new`] for a discretization that builds on every [`Mesh`]: triangle
    /// and polygon meshes alike.
    pub fn on_any_mesh<F>(
        id: impl Into<String>,
        description: impl Into<String>,
        constructor: F,
    ) -> Self
    where
        F: Fn(&dyn Mesh, BoundaryCondition) -> Result<BoxedComplex, DiscretizationError>
            + Send
            + Sync
            + 'static,
    {
        Self {
            id: id.into(),
            description: description.into(),
            preconditions: ANY_MESH.to_string(),
            needs_delaunay: false,
            needs_triangles: false,
            boundary_conditions: Vec::new(),
            boundary_meanings: Vec::new(),
            constructor: Arc::new(constructor),
            intrinsic: None,
        }
    }

    /// The entry with `preconditions`: what the mesh must satisfy beyond being a valid oriented
    /// manifold mesh of the kind the entry builds on (shown in listings and in the error of a
    /// refused mesh).
    pub fn with_preconditions(mut self, preconditions: impl Into<String>) -> Self {
        self.preconditions = preconditions.into();
        self
    }

    /// The entry marked as building on Delaunay meshes only (the conformance suite checks it on
    /// its Delaunay corpus).
    pub fn needing_delaunay(mut self) -> Self {
        self.needs_delaunay = true;
        self
    }

    /// The entry offering `condition` on meshes with boundary, with what it fixes in the complex
    /// (one phrase, e.g. "P1 potentials zero at boundary vertices"). The first condition offered
    /// is the entry's default; offering one again replaces its phrase.
    pub fn with_boundary_condition(
        mut self,
        condition: BoundaryCondition,
        fixes: impl Into<String>,
    ) -> Self {
        match self
            .boundary_conditions
            .iter()
            .position(|&b| b == condition)
        {
            Some(i) => self.boundary_meanings[i] = fixes.into(),
            None => {
                self.boundary_conditions.push(condition);
                self.boundary_meanings.push(fixes.into());
            }
        }
        self
    }

    /// The entry with a constructor from edge lengths: how it builds its complex on an
    /// intrinsic triangulation ([`crate::IntrinsicConstructor`]), which
    /// [`CatalogEntry::on_intrinsic_delaunay`] uses where flips or refinement changed the mesh.
    /// The constructor must give its complex the id it is handed.
    pub fn with_intrinsic_constructor<F>(mut self, constructor: F) -> Self
    where
        F: Fn(
                &TriangleMesh,
                &IntrinsicInput,
                &str,
                BoundaryCondition,
            ) -> Result<BoxedComplex, DiscretizationError>
            + Send
            + Sync
            + 'static,
    {
        self.intrinsic = Some(Arc::new(constructor));
        self
    }

    /// The entry's constructor from edge lengths, if it has one.
    pub fn intrinsic_constructor(&self) -> Option<&IntrinsicConstructor> {
        self.intrinsic.as_ref()
    }

    /// Whether the entry builds on every intrinsic Delaunay triangulation (it has a constructor
    /// from edge lengths); without one, [`CatalogEntry::on_intrinsic_delaunay`] builds only on
    /// meshes that are their own intrinsic Delaunay triangulation.
    pub fn builds_on_intrinsic(&self) -> bool {
        self.intrinsic.is_some()
    }

    /// The stable id, used on command lines, in basis files and in cache names.
    pub fn id(&self) -> &str {
        &self.id
    }

    /// One line: potentials, fields, co-potentials and masses.
    pub fn description(&self) -> &str {
        &self.description
    }

    /// What the mesh must satisfy beyond being a valid oriented manifold mesh.
    pub fn preconditions(&self) -> &str {
        &self.preconditions
    }

    /// Whether the entry builds on triangle meshes only (made with [`CatalogEntry::new`]);
    /// otherwise it builds on polygon meshes too ([`CatalogEntry::on_any_mesh`]).
    pub fn needs_triangles(&self) -> bool {
        self.needs_triangles
    }

    /// Whether construction needs a Delaunay mesh.
    pub fn needs_delaunay(&self) -> bool {
        self.needs_delaunay
    }

    /// The boundary conditions offered on meshes with boundary, the default first (empty: the
    /// entry builds on closed meshes only).
    pub fn boundary_conditions(&self) -> &[BoundaryCondition] {
        &self.boundary_conditions
    }

    /// What `boundary` fixes in this complex, if the entry offers it.
    pub fn boundary_meaning(&self, boundary: BoundaryCondition) -> Option<&str> {
        let i = self
            .boundary_conditions
            .iter()
            .position(|&b| b == boundary)?;
        Some(&self.boundary_meanings[i])
    }

    /// The entry's default boundary condition: the first it offers
    /// ([`BoundaryCondition::default`] if it offers none).
    pub fn default_boundary(&self) -> BoundaryCondition {
        self.boundary_conditions
            .first()
            .copied()
            .unwrap_or_default()
    }

    /// Builds the complex of `mesh` (on a mesh with boundary with the entry's default boundary
    /// condition).
    pub fn build<M: Mesh>(&self, mesh: &M) -> Result<BoxedComplex, DiscretizationError> {
        self.build_with(mesh, self.default_boundary())
    }

    /// Builds the complex of `mesh` with boundary condition `boundary` (which only matters on a
    /// mesh with boundary). Fails with [`DiscretizationError::UnsupportedBoundaryCondition`] for a
    /// condition the entry does not offer on a mesh with boundary, with the constructor's error,
    /// or with [`DiscretizationError::Inconsistent`] if the complex's id is not
    /// [`complex_id`]`(id, mesh, boundary)` (basis files rebuild their complex from that id).
    pub fn build_with<M: Mesh>(
        &self,
        mesh: &M,
        boundary: BoundaryCondition,
    ) -> Result<BoxedComplex, DiscretizationError> {
        if !mesh.topology().is_closed() && !self.boundary_conditions.contains(&boundary) {
            return Err(DiscretizationError::UnsupportedBoundaryCondition {
                discretization: self.id.clone(),
                condition: boundary.name(),
                reason: "its catalog entry does not offer it",
            });
        }
        let complex = (self.constructor)(mesh as &dyn Mesh, boundary)?;
        let expected = complex_id(&self.id, mesh.topology(), boundary);
        if complex.id() != expected {
            return Err(DiscretizationError::Inconsistent(format!(
                "the catalog entry '{}' built a complex with the id '{}'; it must be '{expected}' \
                 (basis files rebuild their complex from it)",
                self.id,
                complex.id()
            )));
        }
        Ok(complex)
    }
}

impl std::fmt::Debug for CatalogEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CatalogEntry")
            .field("id", &self.id)
            .field("needs_delaunay", &self.needs_delaunay)
            .field("needs_triangles", &self.needs_triangles)
            .field("builds_on_intrinsic", &self.intrinsic.is_some())
            .field("boundary_conditions", &self.boundary_conditions)
            .finish_non_exhaustive()
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::{Conforming, MassLumping};
    use tvf_core::generate::{disk, icosphere, quad_torus};

    #[test]
    fn a_triangle_entry_refuses_a_polygon_mesh_naming_itself_and_the_cure() {
        let quads = quad_torus(1.0, 0.4, 8, 6).unwrap();
        let error = conforming("conforming-barycentric")
            .build(&quads)
            .err()
            .unwrap();
        assert_eq!(
            error,
            DiscretizationError::NeedsTriangles {
                discretization: "conforming-barycentric".to_string(),
                polygons: 48
            }
        );
        assert!(error.to_string().contains("--triangulate"), "{error}");
    }

    /// An entry with id `id` that builds the barycentric conforming complex.
    pub(crate) fn conforming(id: &str) -> CatalogEntry {
        CatalogEntry::new(id, "test", |mesh, boundary| -> Result<BoxedComplex, _> {
            Ok(Box::new(Conforming::with_boundary(
                mesh,
                MassLumping::Barycentric,
                boundary,
            )?))
        })
    }

    #[test]
    fn a_complex_must_carry_the_entry_id() {
        let mesh = icosphere(1);
        assert!(conforming("conforming-barycentric").build(&mesh).is_ok());
        let error = conforming("other").build(&mesh).err().unwrap().to_string();
        assert!(error.contains("'conforming-barycentric'"), "{error}");
    }

    #[test]
    fn a_condition_not_offered_is_refused_on_meshes_with_boundary_only() {
        let entry = conforming("conforming-barycentric");
        let closed = icosphere(1);
        let open = disk(2);
        assert!(entry.build(&closed).is_ok());
        assert!(matches!(
            entry.build(&open),
            Err(DiscretizationError::UnsupportedBoundaryCondition { .. })
        ));
        let entry = entry
            .with_boundary_condition(BoundaryCondition::Normal, "first")
            .with_boundary_condition(BoundaryCondition::Normal, "replaced");
        assert_eq!(entry.default_boundary(), BoundaryCondition::Normal);
        assert_eq!(
            entry.boundary_meaning(BoundaryCondition::Normal),
            Some("replaced")
        );
        assert_eq!(entry.boundary_meaning(BoundaryCondition::Tangential), None);
        let built = entry.build(&open).unwrap();
        assert_eq!(built.id(), "conforming-barycentric+normal");
    }
}
