//! What a reader produces before validation, and the step from it to a [`LoadedMesh`].

use super::error::{LoadError, LoadErrorKind};
use crate::mesh::{FaceList, ValidationReport, ValidationWarning};
use crate::{MeshError, SurfaceMesh};
use std::path::Path;

/// A problem found by a reader, with the 1-based line where one applies.
pub(crate) type Located = (Option<usize>, LoadErrorKind);

/// Builds a [`Located`] error at `line`.
pub(crate) fn at(line: usize, kind: LoadErrorKind) -> Located {
    (Some(line), kind)
}

/// Builds a [`Located`] parse error at `line`.
pub(crate) fn parse_error(line: usize, message: impl Into<String>) -> Located {
    // Control characters of the file (a NUL, an escape) are shown escaped, never sent to the
    // terminal as they are.
    let message: String = message
        .into()
        .chars()
        .flat_map(|c| {
            let escaped: Vec<char> = if c.is_control() || c == '\u{feff}' {
                c.escape_default().collect()
            } else {
                vec![c]
            };
            escaped
        })
        .collect();
    at(line, LoadErrorKind::Parse { message })
}

/// Positions and faces exactly as a file lists them (0-based; polygons as polygons).
#[derive(Debug, Clone, Default)]
pub(crate) struct RawMesh {
    pub positions: Vec<[f64; 3]>,
    pub faces: FaceList,
    /// 1-based line of every vertex, or empty for binary files.
    pub vertex_lines: Vec<usize>,
    /// 1-based line of every face, or empty for binary files.
    pub face_lines: Vec<usize>,
}

/// A mesh read from a file: the valid [`SurfaceMesh`] (triangles if every face of the file is
/// one, else polygons) and what validation reported.
#[derive(Debug, Clone)]
pub struct LoadedMesh {
    /// The mesh (unreferenced vertices dropped).
    pub mesh: SurfaceMesh,
    /// Warnings, angle range and the map back to the file's vertex numbers.
    pub report: ValidationReport,
}

impl RawMesh {
    /// Validates the raw data; errors name `path` and, for text files, the line of the
    /// offending vertex or face.
    pub(crate) fn into_loaded(self, path: &Path) -> Result<LoadedMesh, LoadError> {
        let RawMesh {
            positions,
            faces,
            vertex_lines,
            face_lines,
        } = self;
        SurfaceMesh::validated(positions, faces)
            .map(|(mesh, mut report)| {
                for warning in &mut report.warnings {
                    if let ValidationWarning::NonConvexPolygons {
                        first_face,
                        first_line,
                        ..
                    } = warning
                    {
                        *first_line = face_lines.get(*first_face).copied();
                    }
                }
                LoadedMesh { mesh, report }
            })
            .map_err(|error| {
                let line = match &error {
                    MeshError::NonFiniteCoordinate { vertex }
                    | MeshError::NonManifoldVertex { vertex, .. } => vertex_lines.get(*vertex),
                    MeshError::IndexOutOfRange { face, .. }
                    | MeshError::RepeatedVertexInFace { face, .. }
                    | MeshError::ZeroAreaFace { face }
                    | MeshError::TooFewCorners { face, .. }
                    | MeshError::PolygonFolds { face, .. }
                    | MeshError::PolygonNotTriangulable { face } => face_lines.get(*face),
                    MeshError::InconsistentOrientation { face_b, .. }
                    | MeshError::NonOrientable { face_b, .. } => face_lines.get(*face_b),
                    _ => None,
                };
                LoadError {
                    path: path.to_path_buf(),
                    line: line.copied(),
                    kind: LoadErrorKind::Mesh(error),
                }
            })
    }
}
