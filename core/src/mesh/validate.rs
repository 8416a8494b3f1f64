//! Full validation of positions and faces: every check [`TriangleMesh::new`] makes, plus vertex
//! manifoldness, orientability, zero-area faces, unreferenced and duplicate vertices — written
//! once over [`FaceCorners`], so triangle and polygon lists get the same checks; polygons also
//! get the fold check ([`MeshError::PolygonFolds`]).
//!
//! [`TriangleMesh::new`] stays cheap and only guarantees what the topology tables need.
//! [`TriangleMesh::validated`] and [`crate::SurfaceMesh::validated`] are the entry points for
//! data from outside (files, user input); every reader in [`crate::io`] goes through the latter.

use super::error::MeshError;
use super::face_list::FaceCorners;
use super::polygon_outline::PolygonOutline;
use super::topology::check_corners;
use super::triangle_mesh::TriangleMesh;
use super::validation_report::{ValidationReport, ValidationWarning, SMALL_ANGLE_DEG};
use crate::geometry::{add, cross, dot, norm, scale, sub};
use std::collections::HashMap;

/// A face whose `|(p1−p0)×(p2−p0)|` is at most this times its longest squared edge length is
/// reported as zero-area: collinear or coincident corners up to rounding (a 1e-12° angle).
const ZERO_AREA_RELATIVE: f64 = 64.0 * f64::EPSILON;

impl TriangleMesh {
    /// Validates `positions` and `faces` (0-based, counter-clockwise) and builds the mesh.
    ///
    /// Errors, checked in this order: [`MeshError::NoFaces`], [`MeshError::NonFiniteCoordinate`],
    /// [`MeshError::IndexOutOfRange`], [`MeshError::RepeatedVertexInFace`],
    /// [`MeshError::NonManifoldEdge`], [`MeshError::NonManifoldVertex`],
    /// [`MeshError::NonOrientable`], [`MeshError::InconsistentOrientation`],
    /// [`MeshError::ZeroAreaFace`]. All indices in errors are input indices.
    ///
    /// Unreferenced vertices are dropped (the others keep their order; see
    /// [`ValidationReport::original_vertex`]); they, exact duplicate positions, inward normals
    /// of a closed mesh and sliver faces are reported as warnings.
    pub fn validated(
        positions: Vec<[f64; 3]>,
        faces: Vec<[usize; 3]>,
    ) -> Result<(TriangleMesh, ValidationReport), MeshError> {
        check_faces(&positions, &faces)?;
        let kept = KeptVertices::of(&positions, faces.as_slice());
        let faces = faces
            .into_iter()
            .map(|f| f.map(|v| kept.new_index[v]))
            .collect();
        let (positions, mut report) = kept.into_report(positions);
        let mesh = TriangleMesh::new(positions, faces)?;
        if let Some(warning) = inward_components(&mesh) {
            report.warnings.push(warning);
        }
        let (min_angle_deg, max_angle_deg) = mesh.angle_range_deg();
        let small = (0..mesh.face_count())
            .filter(|&t| {
                mesh.corner_angles(t)
                    .iter()
                    .any(|a| a.to_degrees() < SMALL_ANGLE_DEG)
            })
            .count();
        if small > 0 {
            report
                .warnings
                .push(ValidationWarning::SmallAngles { faces: small });
        }
        report.min_angle_deg = min_angle_deg;
        report.max_angle_deg = max_angle_deg;
        Ok((mesh, report))
    }
}

/// Which vertices the faces use, their new numbers once the others are dropped, and the
/// warnings about unreferenced and duplicate vertices.
pub(crate) struct KeptVertices {
    referenced: Vec<bool>,
    /// The new index of every input vertex (`usize::MAX` for a dropped one).
    pub new_index: Vec<usize>,
    warnings: Vec<ValidationWarning>,
}

impl KeptVertices {
    /// The vertices of `positions` that `faces` use (faces already checked: indices in range).
    pub fn of<F: FaceCorners + ?Sized>(positions: &[[f64; 3]], faces: &F) -> Self {
        let mut referenced = vec![false; positions.len()];
        for f in 0..faces.face_count() {
            for &v in faces.corners(f) {
                referenced[v] = true;
            }
        }
        let mut warnings = Vec::new();
        if let Some(first) = referenced.iter().position(|&r| !r) {
            let count = referenced.iter().filter(|&&r| !r).count();
            warnings.push(ValidationWarning::UnreferencedVertices { count, first });
        }
        if let Some(warning) = duplicate_vertices(positions, &referenced) {
            warnings.push(warning);
        }
        let mut new_index = vec![usize::MAX; positions.len()];
        let mut next = 0;
        for (v, &r) in referenced.iter().enumerate() {
            if r {
                new_index[v] = next;
                next += 1;
            }
        }
        Self {
            referenced,
            new_index,
            warnings,
        }
    }

    /// The kept positions (input order) and a report with the warnings so far, the map back to
    /// input vertices, and no angle range yet (NaN until the caller measures it).
    pub fn into_report(self, positions: Vec<[f64; 3]>) -> (Vec<[f64; 3]>, ValidationReport) {
        let input_vertex_count = positions.len();
        let mut original_vertex = Vec::with_capacity(positions.len());
        let mut kept_positions = Vec::with_capacity(positions.len());
        for (v, p) in positions.into_iter().enumerate() {
            if self.referenced[v] {
                original_vertex.push(v);
                kept_positions.push(p);
            }
        }
        let report = ValidationReport {
            warnings: self.warnings,
            original_vertex,
            input_vertex_count,
            min_angle_deg: f64::NAN,
            max_angle_deg: f64::NAN,
        };
        (kept_positions, report)
    }
}

/// The closed components of `mesh` whose signed volume is negative (normals inward), if any.
fn inward_components(mesh: &TriangleMesh) -> Option<ValidationWarning> {
    let count = mesh.component_count();
    let mut volume = vec![0.0; count];
    let mut first_face = vec![usize::MAX; count];
    for (t, (face, &c)) in mesh.faces().iter().zip(mesh.face_components()).enumerate() {
        let [p0, p1, p2] = face.map(|v| mesh.positions()[v]);
        volume[c] += dot(p0, cross(p1, p2)) / 6.0;
        first_face[c] = first_face[c].min(t);
    }
    inward_normals_warning(
        &volume,
        &first_face,
        &mesh.vertex_components(),
        &mesh.boundary_loops(),
    )
}

/// [`ValidationWarning::InwardNormals`] for the closed components (no vertex on a boundary
/// loop) whose signed volume `volume[c]` is negative, if any; `first_face[c]` is component
/// `c`'s lowest face, `vertex_component[v]` the component of vertex `v`.
pub(crate) fn inward_normals_warning(
    volume: &[f64],
    first_face: &[usize],
    vertex_component: &[usize],
    boundary_loops: &[Vec<usize>],
) -> Option<ValidationWarning> {
    let mut open = vec![false; volume.len()];
    for boundary in boundary_loops {
        for &v in boundary {
            open[vertex_component[v]] = true;
        }
    }
    let inward: Vec<usize> = (0..volume.len())
        .filter(|&c| !open[c] && volume[c] < 0.0)
        .collect();
    let &first = inward.first()?;
    Some(ValidationWarning::InwardNormals {
        components: inward.len(),
        first_component: first,
        first_face: first_face[first],
        signed_volume: volume[first],
    })
}

/// Every error check of [`TriangleMesh::validated`], without building anything.
pub fn check_faces(positions: &[[f64; 3]], faces: &[[usize; 3]]) -> Result<(), MeshError> {
    check_combinatorics(positions, faces)?;
    check_triangle_areas(positions, faces)
}

/// Every error check of a face list except the geometric ones: no faces, non-finite
/// coordinates, corners out of range or repeated, non-manifold edges and vertices,
/// non-orientable or inconsistently oriented surfaces.
pub(crate) fn check_combinatorics<F: FaceCorners + ?Sized>(
    positions: &[[f64; 3]],
    faces: &F,
) -> Result<(), MeshError> {
    if faces.face_count() == 0 {
        return Err(MeshError::NoFaces);
    }
    if let Some(vertex) = positions
        .iter()
        .position(|p| p.iter().any(|x| !x.is_finite()))
    {
        return Err(MeshError::NonFiniteCoordinate { vertex });
    }
    for face in 0..faces.face_count() {
        check_corners(face, faces.corners(face), positions.len())?;
    }
    let pairs = face_pairs(faces)?;
    check_vertex_fans(positions.len(), faces, &pairs)?;
    check_orientation(faces.face_count(), &pairs)
}

/// Two faces sharing the undirected edge `(a, b)`, `a < b`.
struct FacePair {
    a: usize,
    b: usize,
    faces: [usize; 2],
    /// Both faces traverse the edge in the same direction.
    same_direction: bool,
}

/// Groups directed half-edges by undirected edge; fails on edges with more than two faces.
fn face_pairs<F: FaceCorners + ?Sized>(faces: &F) -> Result<Vec<FacePair>, MeshError> {
    let mut half_edges: Vec<(usize, usize, usize, bool)> =
        Vec::with_capacity(faces.total_corners());
    for t in 0..faces.face_count() {
        let f = faces.corners(t);
        for c in 0..f.len() {
            let (from, to) = (f[c], f[(c + 1) % f.len()]);
            half_edges.push((from.min(to), from.max(to), t, from < to));
        }
    }
    half_edges.sort_unstable();
    let mut pairs = Vec::with_capacity(half_edges.len() / 2);
    for group in half_edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        let (a, b, t0, forward0) = group[0];
        match group {
            [_] => {}
            [_, (_, _, t1, forward1)] => pairs.push(FacePair {
                a,
                b,
                faces: [t0, *t1],
                same_direction: forward0 == *forward1,
            }),
            _ => {
                return Err(MeshError::NonManifoldEdge {
                    a,
                    b,
                    face_count: group.len(),
                })
            }
        }
    }
    Ok(pairs)
}

/// Union–find root with path halving.
fn root(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Fails if the faces around some vertex form more than one edge-connected fan.
///
/// Union–find over corners (numbered by [`FaceCorners::corner_index`]): two faces sharing edge
/// `(a, b)` join their corners at `a` and at `b`; a manifold vertex ends with all its corners in
/// one set.
fn check_vertex_fans<F: FaceCorners + ?Sized>(
    vertex_count: usize,
    faces: &F,
    pairs: &[FacePair],
) -> Result<(), MeshError> {
    let corner_of = |t: usize, v: usize| {
        let c = faces.corners(t).iter().position(|&w| w == v).unwrap_or(0);
        faces.corner_index(t, c)
    };
    let mut parent: Vec<usize> = (0..faces.total_corners()).collect();
    for pair in pairs {
        let [t0, t1] = pair.faces;
        for v in [pair.a, pair.b] {
            let (r0, r1) = (
                root(&mut parent, corner_of(t0, v)),
                root(&mut parent, corner_of(t1, v)),
            );
            parent[r0.max(r1)] = r0.min(r1);
        }
    }
    let mut fans: Vec<(usize, usize)> = Vec::with_capacity(faces.total_corners());
    for t in 0..faces.face_count() {
        for (c, &v) in faces.corners(t).iter().enumerate() {
            fans.push((v, root(&mut parent, faces.corner_index(t, c))));
        }
    }
    fans.sort_unstable();
    fans.dedup();
    let mut count = vec![0usize; vertex_count];
    for &(v, _) in &fans {
        count[v] += 1;
    }
    match count.iter().position(|&c| c > 1) {
        Some(vertex) => Err(MeshError::NonManifoldVertex {
            vertex,
            fans: count[vertex],
        }),
        None => Ok(()),
    }
}

/// Tries to orient every component consistently by breadth-first search from its first face.
///
/// If some face would need both orientations the surface is non-orientable; otherwise, if any
/// neighbours disagree, it is orientable but inconsistently oriented.
fn check_orientation(face_count: usize, pairs: &[FacePair]) -> Result<(), MeshError> {
    // Compressed adjacency: neighbours of face t are adjacency[offset[t]..offset[t + 1]].
    let mut offset = vec![0usize; face_count + 1];
    for pair in pairs {
        offset[pair.faces[0] + 1] += 1;
        offset[pair.faces[1] + 1] += 1;
    }
    for t in 0..face_count {
        offset[t + 1] += offset[t];
    }
    let mut fill = offset.clone();
    let mut adjacency = vec![(0usize, false); offset[face_count]];
    for pair in pairs {
        let [t0, t1] = pair.faces;
        adjacency[fill[t0]] = (t1, pair.same_direction);
        fill[t0] += 1;
        adjacency[fill[t1]] = (t0, pair.same_direction);
        fill[t1] += 1;
    }
    // flipped[t]: whether face t must be reversed to agree with the first face of its component.
    let mut flipped: Vec<Option<bool>> = vec![None; face_count];
    let mut queue = std::collections::VecDeque::new();
    for start in 0..face_count {
        if flipped[start].is_some() {
            continue;
        }
        flipped[start] = Some(false);
        queue.push_back(start);
        while let Some(t) = queue.pop_front() {
            let flip_t = flipped[t] == Some(true);
            for &(u, same) in &adjacency[offset[t]..offset[t + 1]] {
                let wanted = flip_t ^ same;
                match flipped[u] {
                    None => {
                        flipped[u] = Some(wanted);
                        queue.push_back(u);
                    }
                    Some(actual) if actual != wanted => {
                        return Err(MeshError::NonOrientable {
                            face_a: start,
                            face_b: u,
                        })
                    }
                    Some(_) => {}
                }
            }
        }
    }
    match pairs.iter().find(|p| p.same_direction) {
        Some(pair) => Err(MeshError::InconsistentOrientation {
            face_a: pair.faces[0],
            face_b: pair.faces[1],
            a: pair.a,
            b: pair.b,
        }),
        None => Ok(()),
    }
}

/// Fails on the first face whose area is zero up to rounding (see [`ZERO_AREA_RELATIVE`]).
fn check_triangle_areas(positions: &[[f64; 3]], faces: &[[usize; 3]]) -> Result<(), MeshError> {
    for (face, f) in faces.iter().enumerate() {
        let [p0, p1, p2] = f.map(|i| positions[i]);
        let twice_area = norm(cross(sub(p1, p0), sub(p2, p0)));
        let longest_squared = [sub(p1, p0), sub(p2, p1), sub(p0, p2)]
            .iter()
            .map(|e| e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
            .fold(0.0, f64::max);
        if twice_area <= ZERO_AREA_RELATIVE * longest_squared {
            return Err(MeshError::ZeroAreaFace { face });
        }
    }
    Ok(())
}

/// Fails on the first polygon whose vector area is zero up to rounding (twice its length at most
/// [`ZERO_AREA_RELATIVE`] times the longest squared side, as for triangles) or that folds over
/// itself ([`MeshError::PolygonFolds`]: seen along its vector area, two sides that are not
/// neighbours meet).
pub(crate) fn check_polygon_geometry<F: FaceCorners + ?Sized>(
    positions: &[[f64; 3]],
    faces: &F,
) -> Result<(), MeshError> {
    for face in 0..faces.face_count() {
        let corners: Vec<[f64; 3]> = faces.corners(face).iter().map(|&v| positions[v]).collect();
        let area = polygon_vector_area(&corners);
        let n = corners.len();
        let longest_squared = (0..n)
            .map(|c| {
                let e = sub(corners[(c + 1) % n], corners[c]);
                dot(e, e)
            })
            .fold(0.0, f64::max);
        if 2.0 * norm(area) <= ZERO_AREA_RELATIVE * longest_squared {
            return Err(MeshError::ZeroAreaFace { face });
        }
        if n == 3 {
            continue;
        }
        if let Some((side, other_side)) = PolygonOutline::new(&corners, area).crossing_sides() {
            return Err(MeshError::PolygonFolds {
                face,
                side,
                other_side,
            });
        }
    }
    Ok(())
}

/// The polygons (more than three corners) that are not convex seen along their vector area:
/// how many, and the first.
pub(crate) fn non_convex_polygons<F: FaceCorners + ?Sized>(
    positions: &[[f64; 3]],
    faces: &F,
) -> Option<(usize, usize)> {
    let mut found: Option<(usize, usize)> = None;
    for face in 0..faces.face_count() {
        let corners: Vec<[f64; 3]> = faces.corners(face).iter().map(|&v| positions[v]).collect();
        if corners.len() > 3
            && !PolygonOutline::new(&corners, polygon_vector_area(&corners)).is_convex()
        {
            let (count, first) = found.unwrap_or((0, face));
            found = Some((count + 1, first));
        }
    }
    found
}

/// The vector area `½ Σ_c p_c × p_{c+1}` of a polygon with corners `corners` (counter-clockwise),
/// summed relative to the first corner so that it does not depend on the origin: its direction is
/// the polygon's normal and its length the area of a planar polygon (units of length²).
pub fn polygon_vector_area(corners: &[[f64; 3]]) -> [f64; 3] {
    let origin = corners[0];
    let mut sum = [0.0; 3];
    for c in 1..corners.len().saturating_sub(1) {
        sum = add(
            sum,
            cross(sub(corners[c], origin), sub(corners[c + 1], origin)),
        );
    }
    scale(sum, 0.5)
}

/// The average of a polygon's corners, `(p_0 + … + p_{n−1}) / n` (its "centroid" in de Goes et
/// al. 2020).
pub fn polygon_centroid(corners: &[[f64; 3]]) -> [f64; 3] {
    let n = corners.len() as f64;
    std::array::from_fn(|k| corners.iter().map(|p| p[k]).sum::<f64>() / n)
}

/// Reports referenced vertices whose position (bit for bit, `-0.0 = 0.0`) repeats an earlier one.
fn duplicate_vertices(positions: &[[f64; 3]], referenced: &[bool]) -> Option<ValidationWarning> {
    let mut seen: HashMap<[u64; 3], usize> = HashMap::with_capacity(positions.len());
    let mut count = 0;
    let mut first = None;
    for (v, p) in positions.iter().enumerate() {
        if !referenced[v] {
            continue;
        }
        let key = p.map(|x| (x + 0.0).to_bits());
        match seen.get(&key) {
            Some(&earlier) => {
                count += 1;
                first.get_or_insert((v, earlier));
            }
            None => {
                seen.insert(key, v);
            }
        }
    }
    first.map(
        |(first, duplicate_of)| ValidationWarning::DuplicateVertices {
            count,
            first,
            duplicate_of,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Vec<[f64; 3]> {
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ]
    }

    #[test]
    fn flipped_square_is_inconsistent_not_non_orientable() {
        assert!(TriangleMesh::validated(square(), vec![[0, 1, 2], [0, 2, 3]]).is_ok());
        assert!(matches!(
            check_faces(&square(), &[[0, 1, 2], [0, 3, 2]]),
            Err(MeshError::InconsistentOrientation { a: 0, b: 2, .. })
        ));
    }

    #[test]
    fn bowtie_is_a_non_manifold_vertex() {
        let mut positions = square();
        positions.extend([[-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]);
        let faces = vec![[0, 1, 2], [0, 4, 5]];
        assert_eq!(
            check_faces(&positions, &faces),
            Err(MeshError::NonManifoldVertex { vertex: 0, fans: 2 })
        );
    }

    #[test]
    fn unreferenced_vertices_are_dropped_and_reported() {
        let mut positions = square();
        positions.insert(0, [5.0, 5.0, 5.0]);
        let (mesh, report) =
            TriangleMesh::validated(positions, vec![[1, 2, 3], [1, 3, 4]]).unwrap();
        assert_eq!(mesh.vertex_count(), 4);
        assert_eq!(report.unreferenced_vertices(), 1);
        assert_eq!(report.original_vertex, vec![1, 2, 3, 4]);
        assert_eq!(mesh.faces()[0], [0, 1, 2]);
        assert!((report.max_angle_deg - 90.0).abs() < 1e-12);
        assert!((report.min_angle_deg - 45.0).abs() < 1e-12);
    }

    #[test]
    fn collinear_face_has_zero_area() {
        let positions = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.3, 0.0, 0.0]];
        assert_eq!(
            check_faces(&positions, &[[0, 1, 2]]),
            Err(MeshError::ZeroAreaFace { face: 0 })
        );
    }
}
