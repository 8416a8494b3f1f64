//! Meshes: triangle meshes ([`TriangleMesh`]), polygon meshes ([`PolygonMesh`]) and what a
//! complex is built on, either of them ([`SurfaceMesh`]); their topology, surface points,
//! display triangulation, validation and errors.

mod any_mesh;
mod display_triangulation;
mod error;
mod face_list;
mod fingerprint;
mod geometry_range;
mod polygon_mesh;
mod polygon_outline;
mod quality;
mod surface_mesh;
mod surface_point;
mod topology;
mod triangle_mesh;
mod validate;
mod validation_report;

pub use any_mesh::Mesh;
pub use display_triangulation::DisplayTriangulation;
pub use error::MeshError;
pub use face_list::{FaceCorners, FaceList};
pub use geometry_range::GeometryRangeError;
pub use polygon_mesh::PolygonMesh;
pub use quality::triangle_angles;
pub use surface_mesh::{SurfaceMesh, POINT_WEIGHT_TOLERANCE};
pub use surface_point::{SurfacePoint, SurfacePointError};
pub use topology::{MeshTopology, NO_FACE};
pub use triangle_mesh::TriangleMesh;
pub use validate::{check_faces, polygon_centroid, polygon_vector_area};
pub use validation_report::{ValidationReport, ValidationWarning, SMALL_ANGLE_DEG};
