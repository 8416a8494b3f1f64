//! Intrinsic triangulations of a triangle mesh: the same surface, triangulated by other edges
//! that run straight across the input's faces, known by connectivity and edge lengths only.
//!
//! - [`IntrinsicTriangulation`]: connectivity (several edges between two vertices and edges from
//!   a vertex to itself allowed), edge lengths, geometry from lengths (angles, areas, cotan
//!   weights `⋆1`, vertex areas, the cotan Laplacian), and the integer coordinates that tie it to
//!   the input (why integer coordinates rather than signposts: see its doc).
//! - [`IntrinsicTriangulation::flip_to_delaunay`]: the intrinsic Delaunay triangulation by edge
//!   flips, no vertex inserted; [`IntrinsicTriangulation::refine`] also splits the edges flips
//!   cannot make strictly Delaunay (cocircular interior edges, boundary edges opposite obtuse
//!   angles), inserting vertices with a place on the input ([`InputLocation`]).
//! - [`CommonSubdivision`]: the overlay of the input and the intrinsic triangulation, with point
//!   and tangent-vector maps both ways ([`TrianglePoint`]) and the area each intrinsic face
//!   covers of each input face ([`Overlap`]).
//! - The triangle formulas from three lengths ([`triangle_area`], [`corner_angles`],
//!   [`corner_cotangents`], [`mixed_voronoi_shares`]).
//!
//! ```
//! use tvf_core::generate::{icosphere, jitter};
//! use tvf_core::intrinsic::{IntrinsicTriangulation, TrianglePoint};
//! let mesh = jitter(&icosphere(2), 0.4, 7).unwrap();
//! let mut intrinsic = IntrinsicTriangulation::new(&mesh).unwrap();
//! let flips = intrinsic.flip_to_delaunay().unwrap();
//! assert!(flips > 0 && intrinsic.non_delaunay_edges().is_empty());
//! assert!((intrinsic.total_area() - mesh.total_area()).abs() < 1e-12);
//!
//! // The centroid of input face 0 on the intrinsic triangulation, and back.
//! let overlay = intrinsic.common_subdivision(&mesh).unwrap();
//! let centroid = TrianglePoint { face: 0, barycentric: [1.0 / 3.0; 3] };
//! let there = overlay.to_intrinsic(centroid).unwrap();
//! let back = overlay.to_input(there).unwrap();
//! assert_eq!(back.face, 0);
//! // The intrinsic faces covering input face 0 cover all of it.
//! let covered: f64 = overlay.input_face_overlaps(0).iter().map(|o| o.area).sum();
//! assert!((covered - mesh.face_area(0)).abs() < 1e-12);
//! ```

mod common_subdivision;
mod crossings;
mod curve_ends;
mod delaunay_flips;
mod edge_split;
mod error;
mod intrinsic_geometry;
#[cfg(test)]
mod invariants;
mod length_geometry;
mod normal_coordinates;
mod point_mapping;
#[cfg(test)]
mod property_tests;
mod refine;
#[cfg(test)]
mod shared_mesh_tests;
mod surface_location;
#[cfg(test)]
mod test_meshes;
mod trace;
mod triangulation;

pub use common_subdivision::{Cell, CommonSubdivision, Overlap};
pub use delaunay_flips::DELAUNAY_FLIP_TOLERANCE;
pub use error::IntrinsicError;
pub use length_geometry::{
    corner_angles, corner_cotangents, is_triangle, mixed_voronoi_shares, triangle_area,
};
pub use normal_coordinates::ALONG_INPUT_EDGE;
pub use refine::{RefineOptions, RefineReport, STRICT_DELAUNAY_MARGIN};
pub use surface_location::{InputLocation, TrianglePoint};
pub use triangulation::IntrinsicTriangulation;
