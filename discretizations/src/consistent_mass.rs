//! The consistent (Galerkin) mass of P1 functions, `∫ φ_i φ_j`.

use crate::face_geometry::FaceGeometry;
use sprs::CsMat;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::TriangleMesh;

/// The consistent P1 mass `M[i, j] = Σ_T ∫_T φ_i φ_j = Σ_T |T| (1 + δ_ij) / 12` over the faces
/// `T` holding both vertices (`V × V`, symmetric, units of area; CSR).
///
/// Row `i` sums to a third of the area of the faces around vertex `i` (the barycentric lumped
/// mass, [`crate::MassLumping::Barycentric`]), so `1ᵀ M 1` is the area. Positive definite on the
/// vertices faces use (each face's `|T|/12 · [[2, 1, 1], [1, 2, 1], [1, 1, 2]]` is, with
/// eigenvalues `|T|/12 · (4, 1, 1)`); a vertex no face uses has an empty row and column.
pub fn consistent_p1_mass(mesh: &TriangleMesh, geometry: &FaceGeometry) -> CsMat<f64> {
    assemble_consistent_p1_mass(mesh.vertex_count(), mesh.faces(), &geometry.areas)
}

/// [`consistent_p1_mass`] of `vertex_count` vertices and the faces `faces` with areas `areas`
/// (one each): the mesh's, or an intrinsic triangulation's (where a face may repeat a corner,
/// whose entries then add up).
pub(crate) fn assemble_consistent_p1_mass(
    vertex_count: usize,
    faces: &[[usize; 3]],
    areas: &[f64],
) -> CsMat<f64> {
    let capacity = 9 * faces.len();
    let (mut rows, mut cols, mut values) = (
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
        Vec::with_capacity(capacity),
    );
    for (face, &area) in faces.iter().zip(areas) {
        for a in 0..3 {
            for b in 0..3 {
                rows.push(face[a]);
                cols.push(face[b]);
                values.push(if a == b { area / 6.0 } else { area / 12.0 });
            }
        }
    }
    from_triplets(vertex_count, vertex_count, rows, cols, values)
}
