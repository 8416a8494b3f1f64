//! What validation found that does not stop a mesh from being used: warnings and measures.

use std::fmt;

/// A finding that does not make the mesh unusable.
#[derive(Debug, Clone, PartialEq)]
pub enum ValidationWarning {
    /// Vertices that no face uses; they were dropped (indices renumbered, order kept).
    UnreferencedVertices {
        /// How many were dropped.
        count: usize,
        /// The first one (0-based index in the input).
        first: usize,
    },
    /// Referenced vertices with exactly the same position as an earlier referenced vertex.
    /// They are kept (the faces decide the topology), but they usually mean an unwelded seam.
    DuplicateVertices {
        /// How many vertices repeat an earlier position.
        count: usize,
        /// The first repeating vertex (input index).
        first: usize,
        /// The earlier vertex it repeats (input index).
        duplicate_of: usize,
    },
    /// Closed components (no boundary) that enclose a negative volume: their normals point
    /// inward. Judged per component, so one reversed part of a mesh is found even when the
    /// others outweigh it.
    InwardNormals {
        /// How many closed components point inward.
        components: usize,
        /// The first of them (component ids as in [`crate::TriangleMesh::face_components`]).
        first_component: usize,
        /// The lowest-numbered face of that component.
        first_face: usize,
        /// That component's signed volume (units of length³).
        signed_volume: f64,
    },
    /// Faces with an interior angle below [`SMALL_ANGLE_DEG`] degrees (slivers).
    SmallAngles {
        /// Number of such faces.
        faces: usize,
    },
    /// Polygons (more than three corners) that are not convex seen along their vector area.
    /// They are valid: polygon operators are defined on them, and they are drawn through an
    /// ear-clipped triangulation of their own corners; an entry that needs triangles gets the
    /// same triangulation.
    NonConvexPolygons {
        /// How many.
        count: usize,
        /// The first (face index).
        first_face: usize,
        /// The file line of the first, when the mesh was read from a text file.
        first_line: Option<usize>,
    },
}

/// Threshold (degrees) below which an angle is reported by [`ValidationWarning::SmallAngles`].
pub const SMALL_ANGLE_DEG: f64 = 1.0;

impl ValidationWarning {
    /// A short stable name for machine-readable output, e.g. `"unreferenced_vertices"`.
    pub fn code(&self) -> &'static str {
        match self {
            Self::UnreferencedVertices { .. } => "unreferenced_vertices",
            Self::DuplicateVertices { .. } => "duplicate_vertices",
            Self::InwardNormals { .. } => "inward_normals",
            Self::SmallAngles { .. } => "small_angles",
            Self::NonConvexPolygons { .. } => "non_convex_polygons",
        }
    }
}

impl fmt::Display for ValidationWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnreferencedVertices { count, first } => write!(
                f,
                "{count} unreferenced vertices dropped (first: vertex {first})"
            ),
            Self::DuplicateVertices {
                count,
                first,
                duplicate_of,
            } => write!(
                f,
                "{count} vertices repeat an earlier position exactly \
                 (first: vertex {first} = vertex {duplicate_of})"
            ),
            Self::InwardNormals {
                components,
                first_component,
                first_face,
                signed_volume,
            } => write!(
                f,
                "{components} closed component(s) with a negative signed volume: their normals \
                 point inward (first: component {first_component}, the one with face \
                 {first_face}, signed volume {signed_volume:e})"
            ),
            Self::SmallAngles { faces } => {
                write!(f, "{faces} faces have an angle below {SMALL_ANGLE_DEG}°")
            }
            Self::NonConvexPolygons {
                count,
                first_face,
                first_line,
            } => {
                write!(f, "{count} non-convex polygons (first: face {first_face}")?;
                if let Some(line) = first_line {
                    write!(f, ", line {line}")?;
                }
                write!(f, "); they are drawn ear-clipped")
            }
        }
    }
}

/// What [`crate::TriangleMesh::validated`] and [`crate::SurfaceMesh::validated`] found besides
/// errors.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidationReport {
    /// Every non-fatal finding, in a fixed order (unreferenced, duplicates, normals, angles, non-convex
    /// polygons).
    pub warnings: Vec<ValidationWarning>,
    /// `original_vertex[v]`: the input index of mesh vertex `v` (differs from `v` once
    /// unreferenced vertices were dropped), `V` entries.
    pub original_vertex: Vec<usize>,
    /// Number of input vertices (referenced or not).
    pub input_vertex_count: usize,
    /// Smallest interior angle, degrees.
    pub min_angle_deg: f64,
    /// Largest interior angle, degrees.
    pub max_angle_deg: f64,
}

impl ValidationReport {
    /// Number of unreferenced input vertices that were dropped.
    pub fn unreferenced_vertices(&self) -> usize {
        self.input_vertex_count - self.original_vertex.len()
    }

    /// Number of referenced vertices that repeat an earlier position exactly.
    pub fn duplicate_vertices(&self) -> usize {
        self.warnings
            .iter()
            .map(|w| match w {
                ValidationWarning::DuplicateVertices { count, .. } => *count,
                _ => 0,
            })
            .sum()
    }
}
