//! Errors of the discretization layer.

use thiserror::Error;

/// What can go wrong when building or applying a discretization.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum DiscretizationError {
    /// A vector or list has the wrong length.
    #[error("{what}: expected {expected} entries, found {found}")]
    DimensionMismatch {
        /// What was being passed (e.g. "per-face vectors").
        what: &'static str,
        /// The length the discretization needs.
        expected: usize,
        /// The length that was given.
        found: usize,
    },
    /// A face with zero (or non-finite) area: gradients are undefined on it.
    #[error("face {face} is degenerate (area {area:e}); gradients are undefined on it")]
    DegenerateFace {
        /// Index of the face.
        face: usize,
        /// Its area.
        area: f64,
    },
    /// An input value is NaN or infinite.
    #[error("{what} contains a non-finite value at index {index}")]
    NonFinite {
        /// What was being passed.
        what: &'static str,
        /// The first offending index.
        index: usize,
    },
    /// Entries of a mass that must be positive are not.
    #[error(
        "{what} must be positive: {count} entries are not (the first, entry {first}, is {value:e})"
    )]
    NotPositive {
        /// Which mass (e.g. "M1").
        what: &'static str,
        /// How many entries are not positive.
        count: usize,
        /// The first such entry.
        first: usize,
        /// Its value.
        value: f64,
    },
    /// A sparse mass is not positive definite on its free nodes.
    #[error("{what} is not positive definite on its free nodes:{detail}")]
    NotPositiveDefinite {
        /// Which mass (e.g. "M1 (the Whitney mass)").
        what: &'static str,
        /// Where the Cholesky factorization failed.
        detail: String,
    },
    /// A mass that must be symmetric is not (beyond round-off).
    #[error("{what} is not symmetric: the largest |M − Mᵀ| entry is {asymmetry:e} against a largest entry of {scale:e}")]
    NotSymmetric {
        /// Which mass.
        what: &'static str,
        /// The largest entry of `|M − Mᵀ|`.
        asymmetry: f64,
        /// The largest entry of `|M|`.
        scale: f64,
    },
    /// The diagonal Hodge star on edges (`(cot α + cot β)/2`) is not positive (at most a
    /// round-off tolerance): the mesh is not Delaunay.
    #[error("the mesh is not Delaunay: {count} edges have cot α + cot β ≤ {tolerance:e} (the first is edge {first}, cot α + cot β = {value:.3e}); the diagonal Hodge star ⋆1 needs a Delaunay mesh: build on the intrinsic Delaunay triangulation of the mesh instead (tvf: --intrinsic-delaunay, Python: intrinsic_delaunay=True)")]
    NotDelaunay {
        /// Number of edges with `cot α + cot β` at most the tolerance.
        count: usize,
        /// The first such edge.
        first: usize,
        /// Its `cot α + cot β`.
        value: f64,
        /// The tolerance below which `cot α + cot β` counts as not positive.
        tolerance: f64,
    },
    /// After intrinsic Delaunay flipping some edges still have `⋆1` at most the tolerance:
    /// interior edges between cocircular triangles (`⋆1 = 0`: the dual edge has no length) or
    /// boundary edges opposite an obtuse angle (never flipped). Refinement splits them.
    #[error("after intrinsic Delaunay flipping {count} edges of the intrinsic triangulation still have cot α + cot β ≤ {tolerance:e} (the first {shown}: {edges:?}, the first with {value:.3e}): cocircular neighbours (⋆1 = 0) or boundary edges opposite an obtuse angle, on which DEC's ⋆1 is not positive; use intrinsic Delaunay refinement, which splits them (tvf: --intrinsic-delaunay=refine, Python: intrinsic_delaunay=\"refine\")", shown = .edges.len())]
    NotStrictlyDelaunayAfterFlips {
        /// Number of intrinsic edges with `cot α + cot β` at most the tolerance.
        count: usize,
        /// The first of them (at most 10), intrinsic edge indices.
        edges: Vec<usize>,
        /// `cot α + cot β` of the first.
        value: f64,
        /// The tolerance below which `cot α + cot β` counts as not positive.
        tolerance: f64,
    },
    /// The intrinsic Delaunay triangulation of the mesh or its correspondence with the mesh
    /// could not be computed.
    #[error("the intrinsic Delaunay triangulation could not be built: {0}")]
    Intrinsic(String),
    /// A catalog entry without a constructor from edge lengths was asked to build on an
    /// intrinsic triangulation the flips or refinement changed.
    #[error("the discretization '{discretization}' cannot be built on an intrinsic triangulation: it reads vertex positions, and its catalog entry gives no constructor from edge lengths (`tvf discretizations` marks the entries that have one)")]
    NotIntrinsic {
        /// The entry's id.
        discretization: String,
    },
    /// A discretization of polygon meshes without a constructor from edge lengths (polygonal
    /// DEC) was asked to build on an intrinsic triangulation: it is refused on every mesh.
    #[error("the discretization '{discretization}' does not build on an intrinsic triangulation: it reads vertex positions and the polygons' vector areas, which an intrinsic triangulation (edge lengths only) does not have; it needs none either: its stabilised ⋆1 is positive definite on every mesh, Delaunay or not, so build it on the mesh itself (without --intrinsic-delaunay)")]
    PolygonEntryNotIntrinsic {
        /// The entry's id.
        discretization: String,
    },
    /// A command needs a capability the discretization does not offer.
    #[error("the discretization '{discretization}' does not offer {capability}")]
    MissingCapability {
        /// The complex's id.
        discretization: String,
        /// What is missing.
        capability: &'static str,
    },
    /// The discretization has no complex for this boundary condition on a mesh with boundary.
    #[error("the discretization '{discretization}' does not offer the boundary condition '{condition}' on meshes with boundary: {reason}")]
    UnsupportedBoundaryCondition {
        /// The complex's id.
        discretization: String,
        /// The boundary condition asked for.
        condition: &'static str,
        /// Why, and what is offered instead.
        reason: &'static str,
    },
    /// A value at a node the boundary condition fixes to zero (a Dirichlet node) is not zero: the
    /// vector is not in the complex's space (e.g. a 1-form with a value on a boundary edge given
    /// to a complex of relative forms).
    #[error("{what} has the value {value:e} at node {index}, which the boundary condition fixes to zero")]
    NonzeroOnDirichletNode {
        /// What was being passed.
        what: &'static str,
        /// The first offending node.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A discretization of triangle meshes was asked to build on a polygon mesh.
    #[error(
        "the discretization '{discretization}' works on triangle meshes, and this mesh has \
         {polygons} faces with more than three corners: triangulate it (`--triangulate`, or \
         `tvf triangulate MESH -o OUT`) or choose a discretization of polygon meshes \
         (polygon-dec)"
    )]
    NeedsTriangles {
        /// The discretization's id.
        discretization: String,
        /// How many faces have more than three corners.
        polygons: usize,
    },
    /// The matrices of a complex do not fit together.
    #[error("inconsistent complex: {0}")]
    Inconsistent(String),
    /// A face index is out of range.
    #[error("face {face} is out of range (the mesh has {face_count} faces)")]
    FaceOutOfRange {
        /// The requested face.
        face: usize,
        /// Number of faces.
        face_count: usize,
    },
}
