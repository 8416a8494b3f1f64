//! Rigid motions of a mesh (rotation about an axis through the origin, then translation).

use crate::geometry::{add, cross, dot, norm, scale};
use crate::{MeshError, TriangleMesh};

/// Rotates every vertex by `angle` radians about `axis` (right-hand rule, axis through the
/// origin; need not be unit length), then adds `translation`. Faces and their numbering are
/// unchanged, so every topological array of the result equals the input's.
///
/// A zero `axis` means no rotation. Fails only if the parameters are not finite
/// ([`MeshError::NonFiniteCoordinate`]).
pub fn rigid_motion(
    mesh: &TriangleMesh,
    axis: [f64; 3],
    angle: f64,
    translation: [f64; 3],
) -> Result<TriangleMesh, MeshError> {
    let positions = rigidly_moved(mesh.positions(), axis, angle, translation);
    TriangleMesh::new(positions, mesh.faces().to_vec())
}

/// The positions `positions` rotated by `angle` radians about `axis` (right-hand rule, axis
/// through the origin; need not be unit length; a zero axis means no rotation), then translated
/// by `translation`: the vertices of [`rigid_motion`], for a mesh of any kind.
pub fn rigidly_moved(
    positions: &[[f64; 3]],
    axis: [f64; 3],
    angle: f64,
    translation: [f64; 3],
) -> Vec<[f64; 3]> {
    let length = norm(axis);
    let unit = if length > 0.0 {
        scale(axis, 1.0 / length)
    } else {
        [0.0, 0.0, 1.0]
    };
    let angle = if length > 0.0 { angle } else { 0.0 };
    let (sin, cos) = angle.sin_cos();
    // Rodrigues: p cos + (k × p) sin + k (k·p)(1 − cos).
    positions
        .iter()
        .map(|&p| {
            let rotated = add(
                add(scale(p, cos), scale(cross(unit, p), sin)),
                scale(unit, dot(unit, p) * (1.0 - cos)),
            );
            add(rotated, translation)
        })
        .collect()
}
