//! Convergence against exact spectra: discretizations on refinement sequences of surfaces whose
//! Hodge–Laplacian spectrum is known in closed form — the unit sphere and the unit hemisphere
//! under both boundary conditions — with the relative error of the lowest eigenvalues of each
//! family per level, the observed orders and the time of each basis.
//!
//! On the unit sphere every Laplace–Beltrami eigenvalue `l(l+1)` (`l ≥ 1`, multiplicity
//! `2l + 1`) appears once in each family: integrable fields are gradients of eigenfunctions,
//! co-integrable ones their rotations. On the upper unit hemisphere the eigenfunctions are the
//! spherical harmonics `Y_l^m` that are odd (Dirichlet: `l + m` odd, `l` of them per degree) or
//! even (Neumann: `l + m` even, `l + 1` per degree) across the equator. The family whose
//! potentials the boundary condition fixes gets the Dirichlet spectrum, the other the Neumann
//! spectrum: with `tangential` (potentials free, co-potentials zero on the boundary) the
//! integrable family is Neumann and the co-integrable one Dirichlet; with `normal` the other way
//! round.
//!
//! Each surface comes as triangle meshes (icospheres, ring hemispheres) and as quad meshes
//! (refined cube-spheres and their upper halves), the latter for discretizations that accept
//! polygon meshes (`polygon-dec`). The meshes are inscribed (vertices on the surface), so their
//! geometry converges at `O(h²)` too, and that error is part of what is measured.

use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};
use std::time::Instant;
use tvf_conformance::accuracy_meshes::Sequence;
use tvf_conformance::convergence_checks::spherical_eigenvalues;
pub use tvf_conformance::convergence_checks::{fitted_order, mean_edge_length};
use tvf_conformance::corpus::delaunay_flips;
use tvf_core::discretization::{BoundaryCondition, HodgeComplex};
use tvf_core::generate::{cube_sphere, hemisphere, icosphere};
use tvf_core::mesh::FaceList;
use tvf_core::{SurfaceMesh, TriangleMesh};
use tvf_discretizations::CatalogEntry;
use tvf_spectral::{compute_basis, BasisRequest, FieldFamily};

/// A surface with a known spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Surface {
    /// The unit sphere, by icospheres (`20·4^level` faces).
    Sphere,
    /// The upper unit hemisphere, by ring meshes with `2·2^level` rings (`6·rings²` faces:
    /// 96, 384, 1536, 6144 for levels 1 to 4, close to the icospheres' 80, 320, 1280, 5120)
    /// made Delaunay by edge flips (so that entries needing a Delaunay mesh run too), under a
    /// boundary condition.
    Hemisphere(BoundaryCondition),
    /// The unit sphere, by cube-spheres of `n = 2^(level+1)` quads along each cube edge (`6n²`
    /// non-planar quads: 96, 384, 1536, 6144 for levels 1 to 4).
    QuadSphere,
    /// The upper unit hemisphere, by the upper halves of those cube-spheres (`3n²` quads: 48,
    /// 192, 768, 3072 for levels 1 to 4; the equator is a line of the grid), under a boundary
    /// condition.
    QuadHemisphere(BoundaryCondition),
    /// The unit sphere by the icospheres of [`Surface::Sphere`] with every vertex moved by up to
    /// 0.3 of its shortest edge and put back on the sphere, made Delaunay by flips: irregular
    /// refinements (an icosphere's near-equilateral triangles favour stars that are exact on
    /// equilateral triangles). A new random draw per level
    /// (`tvf_conformance::accuracy_meshes::Sequence`).
    JitteredSphere,
    /// The hemisphere of [`Surface::Hemisphere`] jittered the same way (equator vertices stay on
    /// the equator), under a boundary condition.
    JitteredHemisphere(BoundaryCondition),
}

impl Surface {
    /// `sphere`, `hemisphere`, `quad-sphere`, `quad-hemisphere`, `jittered-sphere` or
    /// `jittered-hemisphere`.
    pub fn name(self) -> &'static str {
        match self {
            Surface::Sphere => "sphere",
            Surface::Hemisphere(_) => "hemisphere",
            Surface::QuadSphere => "quad-sphere",
            Surface::QuadHemisphere(_) => "quad-hemisphere",
            Surface::JitteredSphere => "jittered-sphere",
            Surface::JitteredHemisphere(_) => "jittered-hemisphere",
        }
    }

    /// The boundary condition, on a surface with boundary.
    pub fn boundary(self) -> Option<BoundaryCondition> {
        match self {
            Surface::Sphere | Surface::QuadSphere | Surface::JitteredSphere => None,
            Surface::Hemisphere(b)
            | Surface::QuadHemisphere(b)
            | Surface::JitteredHemisphere(b) => Some(b),
        }
    }

    /// Whether the refinements are jittered (irregular).
    pub fn is_jittered(self) -> bool {
        matches!(
            self,
            Surface::JitteredSphere | Surface::JitteredHemisphere(_)
        )
    }

    /// The jittered surfaces: the sphere and the hemisphere under both conditions.
    pub fn all_jittered() -> Vec<Surface> {
        let mut surfaces = vec![Surface::JitteredSphere];
        surfaces.extend(
            BoundaryCondition::ALL
                .into_iter()
                .map(Surface::JitteredHemisphere),
        );
        surfaces
    }

    /// Whether the surface is meshed by quads (for discretizations that accept polygons).
    pub fn has_quads(self) -> bool {
        matches!(self, Surface::QuadSphere | Surface::QuadHemisphere(_))
    }

    /// The quad surfaces of a full study: the quad sphere and the quad hemisphere under both
    /// conditions.
    pub fn all_quads() -> Vec<Surface> {
        let mut surfaces = vec![Surface::QuadSphere];
        surfaces.extend(
            BoundaryCondition::ALL
                .into_iter()
                .map(Surface::QuadHemisphere),
        );
        surfaces
    }

    /// The surfaces of a full study: the sphere and the hemisphere under both conditions.
    pub fn all() -> Vec<Surface> {
        let mut surfaces = vec![Surface::Sphere];
        surfaces.extend(BoundaryCondition::ALL.into_iter().map(Surface::Hemisphere));
        surfaces
    }

    /// The mesh of refinement `level` (`0` the coarsest).
    pub fn mesh(self, level: u32) -> SurfaceMesh {
        let quads = 2usize << level;
        match self {
            Surface::Sphere => icosphere(level).into(),
            Surface::Hemisphere(_) => delaunay_flips(&hemisphere(2 << level)).into(),
            Surface::QuadSphere => cube_sphere(quads).expect("n ≥ 2").into(),
            Surface::QuadHemisphere(_) => upper_half(&cube_sphere(quads).expect("n ≥ 2").into()),
            Surface::JitteredSphere => Sequence::Sphere(true)
                .mesh(level)
                .expect("a jittered icosphere is a valid mesh"),
            Surface::JitteredHemisphere(_) => Sequence::Hemisphere(true)
                .mesh(level)
                .expect("a jittered ring hemisphere is a valid mesh"),
        }
    }

    /// The lowest `count` nonzero eigenvalues of `family`, ascending: the family whose
    /// potentials the boundary condition fixes gets the Dirichlet spectrum of the hemisphere
    /// ([`spherical_eigenvalues`]).
    pub fn exact_eigenvalues(self, family: FieldFamily, count: usize) -> Vec<f64> {
        let dirichlet = self.boundary().map(|boundary| {
            matches!(
                (boundary, family),
                (BoundaryCondition::Tangential, FieldFamily::Cointegrable)
                    | (BoundaryCondition::Normal, FieldFamily::Integrable)
            )
        });
        spherical_eigenvalues(dirichlet, count)
    }
}

/// The faces of `mesh` whose corners all have `z ≥ 0` (on an even cube-sphere, the upper
/// hemisphere: the equator `z = 0` is a grid line).
fn upper_half(mesh: &SurfaceMesh) -> SurfaceMesh {
    let mut faces = FaceList::new();
    for f in 0..mesh.face_count() {
        let corners = mesh.face(f);
        if corners.iter().all(|&v| mesh.positions()[v][2] >= -1e-12) {
            faces.push(corners);
        }
    }
    SurfaceMesh::validated(mesh.positions().to_vec(), faces)
        .expect("the upper half of a cube-sphere is a valid mesh")
        .0
}

/// What a candidate runs to build its complex on a mesh under a boundary condition; errors are
/// reported with the candidate's name.
pub type CandidateBuilder<'a> = Box<
    dyn Fn(&SurfaceMesh, BoundaryCondition) -> Result<Box<dyn HodgeComplex>, String>
        + Send
        + Sync
        + 'a,
>;

/// A discretization under study: a name and a constructor from a mesh and a boundary
/// condition (a catalog entry, a parameterised entry, a researcher's own).
pub struct Candidate<'a> {
    /// Shown in tables and plots.
    pub name: String,
    /// Builds the complex.
    pub build: CandidateBuilder<'a>,
}

impl<'a> Candidate<'a> {
    /// A candidate named `name` built by `build` on triangle meshes (the quad surfaces are
    /// refused with an error naming the candidate).
    pub fn new(
        name: impl Into<String>,
        build: impl Fn(&TriangleMesh, BoundaryCondition) -> Result<Box<dyn HodgeComplex>, String>
            + Send
            + Sync
            + 'a,
    ) -> Self {
        Self::on_any_mesh(name, move |mesh, boundary| match mesh.as_triangles() {
            Some(triangles) => build(triangles, boundary),
            None => Err("builds on triangle meshes only, not on the quad surfaces".to_string()),
        })
    }

    /// A candidate named `name` built by `build` on meshes of any faces.
    pub fn on_any_mesh(
        name: impl Into<String>,
        build: impl Fn(&SurfaceMesh, BoundaryCondition) -> Result<Box<dyn HodgeComplex>, String>
            + Send
            + Sync
            + 'a,
    ) -> Self {
        Self {
            name: name.into(),
            build: Box::new(build),
        }
    }

    /// The catalog entry `entry`, named by its id; a refused mesh is reported with what the
    /// entry needs.
    pub fn from_entry(entry: &'a CatalogEntry) -> Self {
        Self::on_any_mesh(entry.id(), move |mesh, boundary| {
            entry
                .build_with(mesh, boundary)
                .map_err(|e| format!("cannot build (needs: {}): {e}", entry.preconditions()))
        })
    }
}

/// What a study runs.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvergenceConfig {
    /// The surfaces.
    pub surfaces: Vec<Surface>,
    /// Refinement levels, ascending.
    pub levels: Vec<u32>,
    /// Eigenvalues compared per family (the lowest nonzero ones).
    pub eigenvalues: usize,
}

impl Default for ConvergenceConfig {
    fn default() -> Self {
        Self {
            surfaces: Surface::all(),
            levels: (1..=4).collect(),
            eigenvalues: 24,
        }
    }
}

/// One candidate on one level of one surface; serialized with the keys of its fields, the
/// surface as `surface` and `boundary` (see [`Surface`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelRow {
    /// The candidate's name.
    pub discretization: String,
    /// The surface.
    #[serde(flatten)]
    pub surface: Surface,
    /// Refinement level.
    pub level: u32,
    /// Faces of the mesh.
    pub faces: usize,
    /// Mean edge length `h` (units of the unit radius).
    pub h: f64,
    /// Largest relative error `|λ_h − λ| / λ` of the lowest eigenvalues of the integrable family.
    pub integrable_error: f64,
    /// The same for the co-integrable family.
    pub cointegrable_error: f64,
    /// Wall-clock seconds to build the complex and compute the basis.
    pub seconds: f64,
}

impl LevelRow {
    /// One line for progress logs: candidate, surface, level, faces, both errors, seconds.
    pub fn summary(&self) -> String {
        format!(
            "{} on the {}{} level {} ({} faces): errors {:.2e} / {:.2e}, {:.2} s",
            self.discretization,
            self.surface.name(),
            self.surface
                .boundary()
                .map_or(String::new(), |b| format!(" ({})", b.name())),
            self.level,
            self.faces,
            self.integrable_error,
            self.cointegrable_error,
            self.seconds
        )
    }

    /// The error of `family` (harmonic: 0).
    pub fn error(&self, family: FieldFamily) -> f64 {
        match family {
            FieldFamily::Integrable => self.integrable_error,
            FieldFamily::Cointegrable => self.cointegrable_error,
            FieldFamily::Harmonic => 0.0,
        }
    }
}

/// The observed order of one family of one candidate on one surface; serialized with the keys
/// of its fields, the surface as `surface` and `boundary`, an order that could not be fitted
/// (not finite) as `null` by `serde_json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObservedOrder {
    /// The candidate's name.
    pub discretization: String,
    /// The surface.
    #[serde(flatten)]
    pub surface: Surface,
    /// `integrable` or `cointegrable`.
    #[serde(serialize_with = "family_name")]
    pub family: FieldFamily,
    /// The least-squares slope of `log error` against `log h` over the levels (all but the
    /// coarsest when there are three or more): the error behaves like `h^order`.
    pub order: f64,
}

/// The result of a study: one row per candidate, surface and level, and the orders (serialized
/// as `rows` and `orders`).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct ConvergenceReport {
    /// Rows, by candidate, then surface, then level.
    pub rows: Vec<LevelRow>,
    /// One order per candidate, surface and family.
    pub orders: Vec<ObservedOrder>,
}

/// A family by its name (`integrable`, `cointegrable`, `harmonic`).
fn family_name<S: Serializer>(family: &FieldFamily, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(family.name())
}

/// A surface as two entries: `surface` (its name) and `boundary` (the boundary condition's
/// name, `null` on the sphere).
impl Serialize for Surface {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(2))?;
        map.serialize_entry("surface", self.name())?;
        map.serialize_entry("boundary", &self.boundary().map(|b| b.name()))?;
        map.end()
    }
}

/// Why a study stopped.
#[derive(Debug, thiserror::Error)]
pub enum ConvergenceError {
    /// A candidate could not be built on a mesh.
    #[error("{discretization} on the {surface} (level {level}): {reason}")]
    Build {
        /// The candidate.
        discretization: String,
        /// The surface.
        surface: &'static str,
        /// The level.
        level: u32,
        /// The constructor's message.
        reason: String,
    },
    /// The basis could not be computed or holds too few eigenvalues.
    #[error("{discretization} on the {surface} (level {level}): {reason}")]
    Basis {
        /// The candidate.
        discretization: String,
        /// The surface.
        surface: &'static str,
        /// The level.
        level: u32,
        /// What went wrong.
        reason: String,
    },
    /// A study needs levels and eigenvalues.
    #[error("a convergence study needs at least one level, surface and eigenvalue")]
    Empty,
    /// Two candidates of one name (their rows could not be told apart).
    #[error("'{0}' is given twice: name each discretization once")]
    Duplicate(String),
}

/// Runs every candidate on every level of every surface of `config`; `progress` is called after
/// each basis with the number of bases done, the number of bases in the study and the new row.
pub fn run_convergence(
    candidates: &[Candidate<'_>],
    config: &ConvergenceConfig,
    progress: &dyn Fn(usize, usize, &LevelRow),
) -> Result<ConvergenceReport, ConvergenceError> {
    if config.levels.is_empty() || config.surfaces.is_empty() || config.eigenvalues == 0 {
        return Err(ConvergenceError::Empty);
    }
    let repeated = candidates.iter().enumerate().find_map(|(k, candidate)| {
        let seen = candidates[..k].iter().any(|c| c.name == candidate.name);
        seen.then_some(candidate)
    });
    if let Some(candidate) = repeated {
        return Err(ConvergenceError::Duplicate(candidate.name.clone()));
    }
    let total = candidates.len() * config.surfaces.len() * config.levels.len();
    let mut rows = Vec::new();
    for &surface in &config.surfaces {
        for &level in &config.levels {
            let mesh = surface.mesh(level);
            let h = mean_edge_length(&mesh);
            for candidate in candidates {
                let row = measure(candidate, surface, level, &mesh, h, config.eigenvalues)?;
                progress(rows.len() + 1, total, &row);
                rows.push(row);
            }
        }
    }
    rows.sort_by(|a, b| {
        let position = |r: &LevelRow| {
            candidates
                .iter()
                .position(|c| c.name == r.discretization)
                .unwrap_or(usize::MAX)
        };
        let surface = |r: &LevelRow| config.surfaces.iter().position(|s| *s == r.surface);
        (position(a), surface(a), a.level).cmp(&(position(b), surface(b), b.level))
    });
    let orders = observed_orders(candidates, &config.surfaces, &rows);
    Ok(ConvergenceReport { rows, orders })
}

/// One basis: build, compute, compare.
fn measure(
    candidate: &Candidate<'_>,
    surface: Surface,
    level: u32,
    mesh: &SurfaceMesh,
    h: f64,
    count: usize,
) -> Result<LevelRow, ConvergenceError> {
    let start = Instant::now();
    let boundary = surface.boundary().unwrap_or_default();
    let complex = (candidate.build)(mesh, boundary).map_err(|reason| ConvergenceError::Build {
        discretization: candidate.name.clone(),
        surface: surface.name(),
        level,
        reason,
    })?;
    let basis_error = |reason: String| ConvergenceError::Basis {
        discretization: candidate.name.clone(),
        surface: surface.name(),
        level,
        reason,
    };
    let basis = compute_basis(complex.as_ref(), &BasisRequest::pairs(count).with_seed(1))
        .map_err(|e| basis_error(e.to_string()))?;
    let seconds = start.elapsed().as_secs_f64();
    let mut errors = [0.0; 2];
    for (slot, family) in [FieldFamily::Integrable, FieldFamily::Cointegrable]
        .into_iter()
        .enumerate()
    {
        let computed: Vec<f64> = basis
            .eigenvalues()
            .iter()
            .zip(basis.families())
            .filter(|(_, f)| **f == family)
            .map(|(l, _)| *l)
            .collect();
        if computed.len() < count {
            return Err(basis_error(format!(
                "the basis has {} {} eigenvalues, the study compares {count}",
                computed.len(),
                family.name()
            )));
        }
        let exact = surface.exact_eigenvalues(family, count);
        errors[slot] = computed
            .iter()
            .zip(&exact)
            .map(|(c, e)| (c - e).abs() / e)
            .fold(0.0, f64::max);
    }
    if let Some(bad) = errors.iter().find(|e| !e.is_finite()) {
        return Err(basis_error(format!("a relative eigenvalue error is {bad}")));
    }
    Ok(LevelRow {
        discretization: candidate.name.clone(),
        surface,
        level,
        faces: mesh.face_count(),
        h,
        integrable_error: errors[0],
        cointegrable_error: errors[1],
        seconds,
    })
}

/// Orders of every candidate, surface and family.
fn observed_orders(
    candidates: &[Candidate<'_>],
    surfaces: &[Surface],
    rows: &[LevelRow],
) -> Vec<ObservedOrder> {
    let mut orders = Vec::new();
    for candidate in candidates {
        for &surface in surfaces {
            let levels: Vec<&LevelRow> = rows
                .iter()
                .filter(|r| r.discretization == candidate.name && r.surface == surface)
                .collect();
            for family in [FieldFamily::Integrable, FieldFamily::Cointegrable] {
                let points: Vec<(f64, f64)> =
                    levels.iter().map(|r| (r.h, r.error(family))).collect();
                orders.push(ObservedOrder {
                    discretization: candidate.name.clone(),
                    surface,
                    family,
                    order: fitted_order(&points),
                });
            }
        }
    }
    orders
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_spectra_have_the_right_multiplicities() {
        let sphere = Surface::Sphere.exact_eigenvalues(FieldFamily::Integrable, 15);
        assert_eq!(&sphere[..4], &[2.0, 2.0, 2.0, 6.0]);
        assert_eq!(sphere[14], 12.0);
        let tangential = Surface::Hemisphere(BoundaryCondition::Tangential);
        // Neumann (l + m even): 2 of degree 1, 3 of degree 2; Dirichlet (l + m odd): 1, 2, 3.
        assert_eq!(
            tangential.exact_eigenvalues(FieldFamily::Integrable, 5),
            vec![2.0, 2.0, 6.0, 6.0, 6.0]
        );
        assert_eq!(
            tangential.exact_eigenvalues(FieldFamily::Cointegrable, 6),
            vec![2.0, 6.0, 6.0, 12.0, 12.0, 12.0]
        );
        let normal = Surface::Hemisphere(BoundaryCondition::Normal);
        assert_eq!(
            normal.exact_eigenvalues(FieldFamily::Integrable, 3),
            vec![2.0, 6.0, 6.0]
        );
    }

    /// The same discretization twice once interleaved duplicate rows and printed NaN orders:
    /// refused before anything is computed.
    #[test]
    fn a_candidate_given_twice_is_refused() {
        let never = |_: &TriangleMesh, _| -> Result<Box<dyn HodgeComplex>, String> {
            panic!("nothing is built before the names are checked")
        };
        let candidates = [
            Candidate::new("a", never),
            Candidate::new("b", never),
            Candidate::new("a", never),
        ];
        let config = ConvergenceConfig {
            surfaces: vec![Surface::Sphere],
            levels: vec![1, 2],
            eigenvalues: 4,
        };
        let error = run_convergence(&candidates, &config, &|_, _, _| {}).unwrap_err();
        assert!(
            matches!(error, ConvergenceError::Duplicate(ref name) if name == "a"),
            "{error}"
        );
        assert!(error.to_string().contains("'a' is given twice"), "{error}");
    }
}
