//! A triangulation of every polygon by its own corners (no new vertex): what
//! [`crate::SurfaceMesh::triangulated`] turns a polygon mesh into for the entries that need
//! triangles.

use super::error::MeshError;
use super::face_list::{FaceCorners, FaceList};
use super::polygon_outline::PolygonOutline;
use super::validate::polygon_vector_area;

/// The triangles of `faces` over `positions`, face by face: a triangle stays itself, a polygon
/// of `n > 3` corners becomes the `n − 2` triangles of an ear clipping of its corners seen along
/// its vector area (each counter-clockwise seen from where the vector area points, so the
/// orientation is kept). Fails with [`MeshError::PolygonNotTriangulable`] on a polygon where no
/// ear is found (one that folds over itself, or flat up to rounding).
pub(crate) fn triangulate_by_corners(
    positions: &[[f64; 3]],
    faces: &FaceList,
) -> Result<Vec<[usize; 3]>, MeshError> {
    let mut triangles = Vec::with_capacity(faces.total_corners());
    for (f, corners) in faces.iter().enumerate() {
        if corners.len() == 3 {
            triangles.push([corners[0], corners[1], corners[2]]);
            continue;
        }
        let points: Vec<[f64; 3]> = corners.iter().map(|&v| positions[v]).collect();
        let ears = PolygonOutline::new(&points, polygon_vector_area(&points))
            .ear_triangles()
            .ok_or(MeshError::PolygonNotTriangulable { face: f })?;
        triangles.extend(ears.into_iter().map(|ear| ear.map(|c| corners[c])));
    }
    Ok(triangles)
}
