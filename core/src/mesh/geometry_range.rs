//! [`SurfaceMesh::check_geometry_range`]: a valid mesh whose coordinates are so large that its
//! areas overflow `f64` is refused, since angles and every operator built on it would be
//! meaningless.

use super::SurfaceMesh;
use thiserror::Error;

/// The coordinates of a mesh are too large for `f64` arithmetic.
#[derive(Debug, Clone, PartialEq, Error)]
#[error(
    "coordinates up to {largest:e} are too large for f64 arithmetic: the total area is {area} \
     and angles cannot be measured (scale the mesh down)"
)]
pub struct GeometryRangeError {
    /// The largest absolute coordinate.
    pub largest: f64,
    /// The total area, not finite.
    pub area: f64,
}

impl SurfaceMesh {
    /// Refuses the mesh if its total area is not finite (its coordinates overflow `f64`
    /// arithmetic); the error gives the largest coordinate.
    pub fn check_geometry_range(&self) -> Result<(), GeometryRangeError> {
        let area = self.total_area();
        if area.is_finite() {
            return Ok(());
        }
        let largest = self
            .positions()
            .iter()
            .flatten()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        Err(GeometryRangeError { largest, area })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn areas_that_overflow_are_refused_with_the_largest_coordinate() {
        let faces = vec![[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]];
        let tetrahedron = |s: f64| {
            let positions = vec![[s, 0.0, 0.0], [0.0, s, 0.0], [0.0, 0.0, s], [s, s, s]];
            SurfaceMesh::from(crate::TriangleMesh::new(positions, faces.clone()).unwrap())
        };
        assert!(tetrahedron(1.0).check_geometry_range().is_ok());
        let error = tetrahedron(1e300).check_geometry_range().unwrap_err();
        assert_eq!(error.largest, 1e300);
        assert!(
            error
                .to_string()
                .starts_with("coordinates up to 1e300 are too large"),
            "{error}"
        );
    }
}
