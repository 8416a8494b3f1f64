//! The intrinsic Delaunay modifier of catalog entries: [`IntrinsicDelaunay`] (flips only, or
//! refinement), the ids it gives ([`intrinsic_entry_id`], [`split_intrinsic_id`]), the
//! triangulation with its correspondence that an entry builds on ([`IntrinsicInput`]), and
//! [`CatalogEntry::on_intrinsic_delaunay`].
//!
//! **Ids.** The modified entry of `ENTRY` is `ENTRY+intrinsic-delaunay` (flips) or
//! `ENTRY+intrinsic-delaunay-refine` (refinement); on a mesh with boundary the boundary
//! condition follows, `dec-circumcentric+intrinsic-delaunay+normal`. Basis files, complex
//! folders and cache names carry the whole id, so a basis of the intrinsic complex is never taken
//! for one of the input's.

use crate::catalog_entry::{BoxedComplex, CatalogEntry};
use crate::complex_id::complex_id;
use std::sync::Arc;
use tvf_core::discretization::{
    BoundaryCondition, ComplexParts, DiscretizationError, FieldRotation, FieldSampling,
    HodgeComplex, PointEvaluation,
};
use tvf_core::intrinsic::{
    CommonSubdivision, IntrinsicTriangulation, RefineOptions, TrianglePoint,
};
use tvf_core::TriangleMesh;

/// How the intrinsic Delaunay triangulation of a mesh is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum IntrinsicDelaunay {
    /// Edge flips only ([`IntrinsicTriangulation::flip_to_delaunay`]): the same vertices, the
    /// intrinsic Delaunay triangulation unique up to cocircular ties (which do not change its
    /// cotan matrix), comparable with other implementations. Edges whose `⋆1` stays zero
    /// (cocircular neighbours) or negative (boundary edges opposite an obtuse angle) remain.
    #[default]
    Flip,
    /// Intrinsic Delaunay refinement ([`IntrinsicTriangulation::refine`]): flips, then splits the
    /// edges flips cannot make strictly Delaunay, inserting vertices on the input surface (new
    /// potential nodes of vertex-based spaces). Every edge then has `⋆1 > 0`.
    Refine,
}

/// The id suffix of flips only.
const FLIP_SUFFIX: &str = "intrinsic-delaunay";
/// The id suffix of refinement.
const REFINE_SUFFIX: &str = "intrinsic-delaunay-refine";

impl IntrinsicDelaunay {
    /// Both, the default first.
    pub const ALL: [IntrinsicDelaunay; 2] = [IntrinsicDelaunay::Flip, IntrinsicDelaunay::Refine];

    /// The name on command lines and in Python: `flip`, `refine`.
    pub fn name(self) -> &'static str {
        match self {
            IntrinsicDelaunay::Flip => "flip",
            IntrinsicDelaunay::Refine => "refine",
        }
    }

    /// The mode named `name` (`flip` or `refine`).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// What the complex id carries: `intrinsic-delaunay` (flips), `intrinsic-delaunay-refine`.
    pub fn id_suffix(self) -> &'static str {
        match self {
            IntrinsicDelaunay::Flip => FLIP_SUFFIX,
            IntrinsicDelaunay::Refine => REFINE_SUFFIX,
        }
    }
}

/// A mode by name (`flip` or `refine`); the error names both.
pub fn parse_intrinsic_delaunay(value: &str) -> Result<IntrinsicDelaunay, String> {
    IntrinsicDelaunay::from_name(value)
        .ok_or_else(|| format!("'{value}' is not an intrinsic Delaunay mode: flip or refine"))
}

/// The id of catalog entry `entry_id` built on the intrinsic Delaunay triangulation made by
/// `mode`: `{entry_id}+intrinsic-delaunay` or `{entry_id}+intrinsic-delaunay-refine`.
pub fn intrinsic_entry_id(entry_id: &str, mode: IntrinsicDelaunay) -> String {
    format!("{entry_id}+{}", mode.id_suffix())
}

/// Splits the intrinsic suffix off an entry id (the boundary condition already split off, see
/// [`crate::split_complex_id`]): `dec-barycentric+intrinsic-delaunay` → (`dec-barycentric`,
/// `Some(Flip)`); an id without the suffix is returned whole with `None`.
pub fn split_intrinsic_id(id: &str) -> (&str, Option<IntrinsicDelaunay>) {
    match id.rsplit_once('+') {
        Some((entry, FLIP_SUFFIX)) => (entry, Some(IntrinsicDelaunay::Flip)),
        Some((entry, REFINE_SUFFIX)) => (entry, Some(IntrinsicDelaunay::Refine)),
        _ => (id, None),
    }
}

/// The intrinsic Delaunay triangulation of an input mesh with its correspondence: what an entry's
/// constructor from edge lengths builds on ([`CatalogEntry::with_intrinsic_constructor`]).
#[derive(Debug, Clone)]
pub struct IntrinsicInput {
    /// How it was made.
    pub mode: IntrinsicDelaunay,
    /// The triangulation: connectivity and edge lengths.
    pub triangulation: Arc<IntrinsicTriangulation>,
    /// Its common subdivision with the input: points and tangent vectors both ways.
    pub overlay: Arc<CommonSubdivision>,
}

impl IntrinsicInput {
    /// The intrinsic Delaunay triangulation of `mesh` made by `mode`, with its common
    /// subdivision. Fails with [`DiscretizationError::Intrinsic`] naming what failed (a
    /// degenerate face, a limit of flips or insertions).
    pub fn new(mesh: &TriangleMesh, mode: IntrinsicDelaunay) -> Result<Self, DiscretizationError> {
        let failed =
            |e: tvf_core::intrinsic::IntrinsicError| DiscretizationError::Intrinsic(e.to_string());
        let mut triangulation = IntrinsicTriangulation::new(mesh).map_err(failed)?;
        match mode {
            IntrinsicDelaunay::Flip => {
                triangulation.flip_to_delaunay().map_err(failed)?;
            }
            IntrinsicDelaunay::Refine => {
                triangulation
                    .refine(mesh, RefineOptions::default())
                    .map_err(failed)?;
            }
        }
        let overlay = triangulation.common_subdivision(mesh).map_err(failed)?;
        Ok(Self {
            mode,
            triangulation: Arc::new(triangulation),
            overlay: Arc::new(overlay),
        })
    }

    /// Whether the triangulation is the input's: nothing flipped, nothing inserted (a Delaunay
    /// input; for refinement, one whose every edge is strictly Delaunay).
    pub fn is_input(&self) -> bool {
        self.triangulation.flip_count() == 0 && self.triangulation.inserted_vertex_count() == 0
    }

    /// The cell and the intrinsic point of the input point `(face, barycentric)`. Panics if the
    /// point is not one of the input (callers check points against the mesh first, as
    /// [`FieldSampling::sample_weights`] says).
    pub fn locate(&self, face: usize, barycentric: [f64; 3]) -> (usize, TrianglePoint) {
        self.overlay
            .locate_on_intrinsic(TrianglePoint { face, barycentric })
            .unwrap_or_else(|e| panic!("an input point given to an intrinsic complex: {e}"))
    }
}

/// What an entry runs to build its complex on an intrinsic triangulation: the input mesh, its
/// intrinsic Delaunay triangulation, the id the complex must have and the boundary condition in,
/// the complex out. Its spaces live on the intrinsic vertices, edges and faces; its sampling and
/// point evaluation take points of the input's faces (map them with [`IntrinsicInput::locate`])
/// and its field files hold one vector per input face.
pub type IntrinsicConstructor = Arc<
    dyn Fn(
            &TriangleMesh,
            &IntrinsicInput,
            &str,
            BoundaryCondition,
        ) -> Result<BoxedComplex, DiscretizationError>
        + Send
        + Sync,
>;

impl CatalogEntry {
    /// This entry built on the intrinsic Delaunay triangulation of the mesh, made by `mode`: id
    /// [`intrinsic_entry_id`], the same boundary conditions, on triangle meshes.
    ///
    /// When the triangulation is the input's (nothing flipped or inserted), the entry's own
    /// constructor builds the complex on the mesh and only the id changes: every matrix is the
    /// input complex's bit for bit. Otherwise the entry's constructor from edge lengths
    /// ([`CatalogEntry::with_intrinsic_constructor`]) builds it, and an entry without one fails
    /// with [`DiscretizationError::NotIntrinsic`]. An entry of polygon meshes without one
    /// (polygonal DEC, which reads positions and vector areas, and whose stabilised `⋆1` needs
    /// no Delaunay mesh) fails on every mesh with
    /// [`DiscretizationError::PolygonEntryNotIntrinsic`]. Under [`IntrinsicDelaunay::Flip`] a
    /// discretization that refuses non-positive `⋆1` ([`DiscretizationError::NotDelaunay`])
    /// fails with [`DiscretizationError::NotStrictlyDelaunayAfterFlips`], which names the edges
    /// and suggests refinement.
    pub fn on_intrinsic_delaunay(&self, mode: IntrinsicDelaunay) -> CatalogEntry {
        let id = intrinsic_entry_id(self.id(), mode);
        let base = self.clone();
        let entry_id = id.clone();
        let construct = move |mesh: &TriangleMesh, boundary| {
            let input = IntrinsicInput::new(mesh, mode)?;
            let complex_id = complex_id(&entry_id, mesh.topology(), boundary);
            let built = if input.is_input() {
                base.build_with(mesh, boundary).map(|inner| {
                    Box::new(RenamedComplex::new(inner, complex_id, &input)) as BoxedComplex
                })
            } else {
                match base.intrinsic_constructor() {
                    Some(construct) => construct(mesh, &input, &complex_id, boundary),
                    None => Err(DiscretizationError::NotIntrinsic {
                        discretization: base.id().to_string(),
                    }),
                }
            };
            built.map_err(|error| after_flips(error, mode, &input))
        };
        let description = format!(
            "{} — on the intrinsic Delaunay triangulation ({})",
            self.description(),
            match mode {
                IntrinsicDelaunay::Flip => "edge flips",
                IntrinsicDelaunay::Refine => "flips and refinement",
            }
        );
        let mut entry = if !self.needs_triangles() && !self.builds_on_intrinsic() {
            // An entry of polygon meshes: refused on every mesh, polygons included.
            let discretization = self.id().to_string();
            CatalogEntry::on_any_mesh(id, description, move |_, _| {
                Err(DiscretizationError::PolygonEntryNotIntrinsic {
                    discretization: discretization.clone(),
                })
            })
        } else {
            CatalogEntry::new(id, description, construct)
        };
        for &condition in self.boundary_conditions() {
            let meaning = self.boundary_meaning(condition).unwrap_or_default();
            entry = entry.with_boundary_condition(condition, meaning.to_string());
        }
        entry
    }
}

/// `error` of an entry built after flips: a refused `⋆1` becomes
/// [`DiscretizationError::NotStrictlyDelaunayAfterFlips`] naming the intrinsic edges.
fn after_flips(
    error: DiscretizationError,
    mode: IntrinsicDelaunay,
    input: &IntrinsicInput,
) -> DiscretizationError {
    match (error, mode) {
        (DiscretizationError::NotDelaunay { tolerance, .. }, IntrinsicDelaunay::Flip) => {
            let sums = input.triangulation.cotan_sums();
            let refused: Vec<usize> = (0..sums.len()).filter(|&e| sums[e] <= tolerance).collect();
            DiscretizationError::NotStrictlyDelaunayAfterFlips {
                count: refused.len(),
                value: refused.first().map_or(f64::NAN, |&e| sums[e]),
                edges: refused.into_iter().take(10).collect(),
                tolerance,
            }
        }
        (error, _) => error,
    }
}

/// The complex an entry built on a mesh whose intrinsic Delaunay triangulation is the mesh
/// itself, under the intrinsic id: the inner complex's parts renamed, its capabilities as they
/// are.
struct RenamedComplex {
    parts: ComplexParts,
    inner: BoxedComplex,
    triangulation: Arc<IntrinsicTriangulation>,
}

impl RenamedComplex {
    fn new(inner: BoxedComplex, id: String, input: &IntrinsicInput) -> Self {
        Self {
            parts: inner.parts().renamed(id),
            inner,
            triangulation: input.triangulation.clone(),
        }
    }
}

impl HodgeComplex for RenamedComplex {
    fn parts(&self) -> &ComplexParts {
        &self.parts
    }

    fn sampling(&self) -> Option<&dyn FieldSampling> {
        self.inner.sampling()
    }

    fn rotation(&self) -> Option<&dyn FieldRotation> {
        self.inner.rotation()
    }

    fn point_evaluation(&self) -> Option<&dyn PointEvaluation> {
        self.inner.point_evaluation()
    }

    fn intrinsic_triangulation(&self) -> Option<&IntrinsicTriangulation> {
        Some(&self.triangulation)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_carry_the_mode_and_split_back() {
        assert_eq!(
            intrinsic_entry_id("dec-circumcentric", IntrinsicDelaunay::Flip),
            "dec-circumcentric+intrinsic-delaunay"
        );
        let refine = intrinsic_entry_id("x-y", IntrinsicDelaunay::Refine);
        assert_eq!(refine, "x-y+intrinsic-delaunay-refine");
        assert_eq!(
            split_intrinsic_id(&refine),
            ("x-y", Some(IntrinsicDelaunay::Refine))
        );
        assert_eq!(split_intrinsic_id("x-y"), ("x-y", None));
        assert_eq!(split_intrinsic_id("x+y"), ("x+y", None));
        for mode in IntrinsicDelaunay::ALL {
            assert_eq!(parse_intrinsic_delaunay(mode.name()), Ok(mode));
        }
        assert!(parse_intrinsic_delaunay("yes")
            .unwrap_err()
            .contains("flip or refine"));
    }
}
