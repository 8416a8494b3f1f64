//! Intrinsic triangulations of a triangle mesh: the same surface, triangulated by other edges
//! that run straight across the input's faces, known by connectivity and edge lengths only.
//!
//! - [`IntrinsicTriangulation`]: connectivity (several edges between two vertices and edges from
//!   a vertex to itself allowed), edge lengths, geometry from lengths (angles, areas, cotan
//!   weights `⋆1`, vertex areas), and the integer coordinates that tie it to the input.
//! - [`IntrinsicTriangulation::flip_to_delaunay`]: the intrinsic Delaunay triangulation by edge
//!   flips (no vertex inserted); [`IntrinsicTriangulation::refine`] also splits the edges flips
//!   cannot make strictly Delaunay.
//! - [`CommonSubdivision`]: the overlay of the input and the intrinsic triangulation, with point
//!   maps both ways and the area each intrinsic face covers of each input face.
//!
//! ```
//! use tvf_core::generate::{icosphere, jitter};
//! use tvf_core::intrinsic::IntrinsicTriangulation;
//! let mesh = jitter(&icosphere(2), 0.4, 7).unwrap();
//! let mut intrinsic = IntrinsicTriangulation::new(&mesh).unwrap();
//! let flips = intrinsic.flip_to_delaunay().unwrap();
//! assert!(intrinsic.edge_hodge_star().iter().all(|&s| s > -1e-12));
//! assert!((intrinsic.total_area() - mesh.total_area()).abs() < 1e-12);
//! # let _ = flips;
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
pub use triangulation::{IntrinsicTriangulation, NO_HALFEDGE};
