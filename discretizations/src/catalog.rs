//! [`Catalog`]: the discretizations a program offers, as a value. [`Catalog::builtin`] holds tvf's
//! own ([`crate::builtin_catalog`]); a program adds its own entries ([`Catalog::with`]) and hands
//! the catalog to the CLI (`tvf_cli::run`), which looks every id up in it. The free functions
//! [`catalog_entry`] and [`build_complex`] look ids up in the built-in catalog.

use crate::builtin_catalog::builtin_entries;
use crate::catalog_entry::{BoxedComplex, CatalogEntry};
use crate::complex_id::split_complex_id;
use crate::intrinsic_delaunay::split_intrinsic_id;
use std::sync::OnceLock;
use thiserror::Error;
use tvf_core::discretization::{BoundaryCondition, DiscretizationError};
use tvf_core::mesh::Mesh;

/// The id used when none is given: the paper's conforming decomposition, barycentric masses.
pub const DEFAULT_DISCRETIZATION: &str = "conforming-barycentric";

/// The id used when none is given on a mesh with polygons: polygonal DEC (de Goes, Butts,
/// Desbrun 2020), the built-in entry that works on them.
pub const DEFAULT_POLYGON_DISCRETIZATION: &str = "polygon-dec";

/// The id used when none is given on `mesh`: [`DEFAULT_DISCRETIZATION`] on a triangle mesh,
/// [`DEFAULT_POLYGON_DISCRETIZATION`] on a mesh with polygons.
pub fn default_discretization<M: Mesh + ?Sized>(mesh: &M) -> &'static str {
    match mesh.as_triangles() {
        Some(_) => DEFAULT_DISCRETIZATION,
        None => DEFAULT_POLYGON_DISCRETIZATION,
    }
}

/// A list of discretizations with unique kebab-case ids, in the order listings show them.
/// Cheap to clone (the constructors are shared).
///
/// ```
/// use tvf_discretizations::{BoxedComplex, Catalog, CatalogEntry, Conforming, MassLumping};
///
/// let mine = CatalogEntry::new(
///     "conforming-voronoi-closed",
///     "the conforming decomposition, Voronoi masses, closed meshes only",
///     |mesh, boundary| -> Result<BoxedComplex, _> {
///         let complex = Conforming::with_boundary(mesh, MassLumping::Voronoi, boundary)?;
///         Ok(Box::new(complex))
///     },
/// );
/// let catalog = Catalog::builtin().with(mine)?;
/// assert_eq!(catalog.len(), Catalog::builtin().len() + 1);
/// assert!(catalog.get("conforming-voronoi-closed").is_ok());
/// // The same id twice is refused.
/// assert!(catalog.clone().with(catalog.entries()[0].clone()).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct Catalog {
    entries: Vec<CatalogEntry>,
}

/// Why an entry was not added to a catalog.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum CatalogError {
    /// The catalog already has an entry with this id.
    #[error("the catalog already has a discretization with the id '{0}'")]
    DuplicateId(String),
    /// The id is not kebab-case.
    #[error(
        "'{0}' is not a valid discretization id: use lower-case kebab-case (letters a–z, digits \
         and single '-' between them, e.g. 'conforming-barycentric')"
    )]
    InvalidId(String),
}

/// An id the catalog does not know.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("unknown discretization '{id}'; the catalog has: {known}")]
pub struct UnknownDiscretization {
    /// The id asked for.
    pub id: String,
    /// The known ids, comma-separated.
    pub known: String,
}

/// Why [`Catalog::build_complex`] could not build a complex.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CatalogBuildError {
    /// The id names no catalog entry.
    #[error(transparent)]
    Unknown(#[from] UnknownDiscretization),
    /// The entry refused the mesh (a precondition or the boundary condition).
    #[error("cannot build the discretization '{id}' (needs: {preconditions}): {source}")]
    Refused {
        /// The entry's id.
        id: String,
        /// What the entry needs of the mesh ([`CatalogEntry::preconditions`]).
        preconditions: String,
        /// The entry's error.
        source: DiscretizationError,
    },
}

/// Whether `id` is lower-case kebab-case: words of `a–z` and `0–9` joined by single `-`.
pub fn is_kebab_case(id: &str) -> bool {
    !id.is_empty()
        && id.split('-').all(|word| {
            !word.is_empty()
                && word
                    .chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit())
        })
}

impl Catalog {
    /// A catalog without entries.
    pub fn new() -> Self {
        Self::default()
    }

    /// tvf's own discretizations, in the order `tvf discretizations` lists them
    /// ([`DEFAULT_DISCRETIZATION`] first).
    pub fn builtin() -> Self {
        builtin_catalog().clone()
    }

    /// Adds `entry` at the end. Refuses an id that is not kebab-case ([`is_kebab_case`]) or that
    /// the catalog already has.
    pub fn add(&mut self, entry: CatalogEntry) -> Result<(), CatalogError> {
        if !is_kebab_case(entry.id()) {
            return Err(CatalogError::InvalidId(entry.id().to_string()));
        }
        if self.entries.iter().any(|e| e.id() == entry.id()) {
            return Err(CatalogError::DuplicateId(entry.id().to_string()));
        }
        self.entries.push(entry);
        Ok(())
    }

    /// The catalog with `entry` added ([`Catalog::add`]), for chaining:
    /// `Catalog::builtin().with(a)?.with(b)?`.
    pub fn with(mut self, entry: CatalogEntry) -> Result<Self, CatalogError> {
        self.add(entry)?;
        Ok(self)
    }

    /// The entry with id `id`. A complex's id on a mesh with boundary, `{entry id}+{condition}`,
    /// also finds its entry (see [`split_complex_id`]), and so does the id of the entry on the
    /// intrinsic Delaunay triangulation, `{entry id}+intrinsic-delaunay` (see
    /// [`split_intrinsic_id`]; [`Catalog::build_complex`] builds it). The error lists the known
    /// ids.
    pub fn get(&self, id: &str) -> Result<&CatalogEntry, UnknownDiscretization> {
        let id = split_intrinsic_id(split_complex_id(id).0).0;
        self.entries
            .iter()
            .find(|entry| entry.id() == id)
            .ok_or_else(|| UnknownDiscretization {
                id: id.to_string(),
                known: self.ids().collect::<Vec<_>>().join(", "),
            })
    }

    /// Every entry, in order.
    pub fn entries(&self) -> &[CatalogEntry] {
        &self.entries
    }

    /// Every entry, in order.
    pub fn iter(&self) -> std::slice::Iter<'_, CatalogEntry> {
        self.entries.iter()
    }

    /// Every id, in order.
    pub fn ids(&self) -> impl Iterator<Item = &str> + '_ {
        self.entries.iter().map(CatalogEntry::id)
    }

    /// The number of entries.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether the catalog has no entries.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Builds the complex named by `id` on `mesh`: an entry's id (built with `boundary`, the
    /// entry's default if `None`), or a complex id `{entry id}+{condition}` as basis files store
    /// it, whose own condition is used; `{entry id}+intrinsic-delaunay` (or `…-refine`) builds
    /// the entry on the intrinsic Delaunay triangulation
    /// ([`CatalogEntry::on_intrinsic_delaunay`]).
    pub fn build_complex<M: Mesh>(
        &self,
        id: &str,
        boundary: Option<BoundaryCondition>,
        mesh: &M,
    ) -> Result<BoxedComplex, CatalogBuildError> {
        let (entry_id, named_boundary) = split_complex_id(id);
        let (entry_id, intrinsic) = split_intrinsic_id(entry_id);
        let entry = self.get(entry_id)?;
        let modified = intrinsic.map(|mode| entry.on_intrinsic_delaunay(mode));
        let entry = modified.as_ref().unwrap_or(entry);
        let boundary = named_boundary
            .or(boundary)
            .unwrap_or_else(|| entry.default_boundary());
        entry
            .build_with(mesh, boundary)
            .map_err(|source| CatalogBuildError::Refused {
                id: entry.id().to_string(),
                preconditions: entry.preconditions().to_string(),
                source,
            })
    }
}

impl<'a> IntoIterator for &'a Catalog {
    type Item = &'a CatalogEntry;
    type IntoIter = std::slice::Iter<'a, CatalogEntry>;

    fn into_iter(self) -> Self::IntoIter {
        self.entries.iter()
    }
}

/// The built-in catalog, built once and shared ([`Catalog::builtin`] clones it).
pub fn builtin_catalog() -> &'static Catalog {
    static BUILTIN: OnceLock<Catalog> = OnceLock::new();
    BUILTIN.get_or_init(|| {
        let mut catalog = Catalog::new();
        for entry in builtin_entries() {
            let id = entry.id().to_string();
            if let Err(error) = catalog.add(entry) {
                unreachable!("the built-in entry '{id}' is refused: {error}");
            }
        }
        catalog
    })
}

/// The built-in entry with id `id` (or complex id, see [`Catalog::get`]).
pub fn catalog_entry(id: &str) -> Result<&'static CatalogEntry, UnknownDiscretization> {
    builtin_catalog().get(id)
}

/// [`Catalog::build_complex`] on the built-in catalog.
pub fn build_complex<M: Mesh>(
    id: &str,
    boundary: Option<BoundaryCondition>,
    mesh: &M,
) -> Result<BoxedComplex, CatalogBuildError> {
    builtin_catalog().build_complex(id, boundary, mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog_entry::tests::conforming;
    use tvf_core::generate::{disk, icosphere};

    #[test]
    fn builtin_ids_are_unique_kebab_case_and_match_the_built_complex() {
        let mesh = icosphere(1);
        let catalog = Catalog::builtin();
        assert!(!catalog.is_empty());
        assert_eq!(catalog.entries()[0].id(), DEFAULT_DISCRETIZATION);
        for entry in &catalog {
            assert!(is_kebab_case(entry.id()), "{}", entry.id());
            assert_eq!(catalog.get(entry.id()).unwrap().id(), entry.id());
            let complex = entry.build(&mesh).unwrap();
            assert_eq!(complex.id(), entry.id());
            assert_eq!(entry.boundary_conditions(), BoundaryCondition::ALL);
        }
        let unknown = catalog_entry("nope").unwrap_err().to_string();
        assert!(unknown.contains("dec-circumcentric"), "{unknown}");
    }

    #[test]
    fn duplicate_and_malformed_ids_are_refused() {
        let catalog = Catalog::builtin();
        let duplicate = catalog
            .clone()
            .with(conforming(DEFAULT_DISCRETIZATION))
            .unwrap_err();
        assert_eq!(
            duplicate,
            CatalogError::DuplicateId(DEFAULT_DISCRETIZATION.to_string())
        );
        for bad in ["", "Upper", "a--b", "-a", "a-", "a_b", "a+b", "blend-0.5"] {
            assert_eq!(
                catalog.clone().with(conforming(bad)).unwrap_err(),
                CatalogError::InvalidId(bad.to_string()),
                "{bad}"
            );
        }
        assert!(is_kebab_case("blend-lumping-50"));
    }

    #[test]
    fn complex_ids_find_their_entry_and_name_the_condition() {
        let catalog = Catalog::new()
            .with(conforming("conforming-barycentric"))
            .unwrap();
        assert_eq!(catalog.len(), 1);
        let entry = catalog.get("conforming-barycentric+normal").unwrap();
        assert_eq!(entry.id(), "conforming-barycentric");
        // The entry offers no boundary condition: a mesh with boundary is refused, naming why.
        let refused = catalog
            .build_complex("conforming-barycentric+normal", None, &disk(2))
            .err()
            .unwrap();
        assert!(
            matches!(refused, CatalogBuildError::Refused { .. }),
            "{refused}"
        );
        let open = build_complex("conforming-barycentric+normal", None, &disk(2)).unwrap();
        assert_eq!(open.id(), "conforming-barycentric+normal");
        let unknown = catalog.build_complex("dec-barycentric", None, &icosphere(1));
        let message = unknown.err().unwrap().to_string();
        assert!(
            message.contains("unknown discretization 'dec-barycentric'")
                && message.contains("the catalog has: conforming-barycentric"),
            "{message}"
        );
    }
}
