//! [`SurfaceMesh`]: what a complex is built on and what every command loads — a triangle mesh or
//! a polygon mesh — with what both offer: topology, per-face geometry, surface points and a
//! display triangulation.

use super::any_mesh::Mesh;
use super::corner_triangulation::triangulate_by_corners;
use super::error::MeshError;
use super::face_list::{FaceCorners, FaceList};
use super::surface_point::{SurfacePoint, SurfacePointError};
use super::topology::MeshTopology;
use super::validate::{
    check_combinatorics, check_polygon_geometry, inward_normals_warning, non_convex_polygons,
    KeptVertices,
};
use super::validation_report::{ValidationReport, ValidationWarning, SMALL_ANGLE_DEG};
use super::{PolygonMesh, TriangleMesh};
use crate::geometry::{dot, norm, scale, sub};

/// Tolerance on `|Σ w − 1|` of a [`SurfacePoint`]'s weights.
pub const POINT_WEIGHT_TOLERANCE: f64 = 1e-9;

/// An oriented manifold surface mesh: triangles, or polygons of any size ≥ 3.
///
/// A mesh whose faces all have three corners is always [`SurfaceMesh::Triangles`] (the readers
/// and [`SurfaceMesh::validated`] see to it), so every triangle discretization works on it as
/// it always has. The methods here are the ones that mean the same on both kinds: faces as
/// corner lists (edge `c` of a face joins corner `c` to `c + 1`), vector areas, normals and
/// centroids, the topology, surface points and the display triangulation (a triangle mesh is
/// its own).
// A program holds one or two meshes, each owning megabytes of vertex and face arrays: the size
// of the enum's inline part (hundreds of bytes) does not matter, and boxing would only add an
// indirection to every access.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
pub enum SurfaceMesh {
    /// Every face a triangle.
    Triangles(TriangleMesh),
    /// Some face with more than three corners.
    Polygons(PolygonMesh),
}

impl From<TriangleMesh> for SurfaceMesh {
    fn from(mesh: TriangleMesh) -> Self {
        Self::Triangles(mesh)
    }
}

impl From<PolygonMesh> for SurfaceMesh {
    fn from(mesh: PolygonMesh) -> Self {
        Self::Polygons(mesh)
    }
}

impl SurfaceMesh {
    /// Builds a mesh from positions and counter-clockwise faces of any size ≥ 3: a triangle mesh
    /// if every face has three corners, else a polygon mesh. Checks what
    /// [`TriangleMesh::new`] and [`PolygonMesh::new`] check.
    pub fn new(positions: Vec<[f64; 3]>, faces: FaceList) -> Result<Self, MeshError> {
        match faces.to_triangles() {
            Some(triangles) => TriangleMesh::new(positions, triangles).map(Self::Triangles),
            None => PolygonMesh::new(positions, faces).map(Self::Polygons),
        }
    }

    /// Validates positions and faces from outside (files, user input) and builds the mesh: for
    /// triangles [`TriangleMesh::validated`]; for polygons the same checks in the same order
    /// (corners at least three, in range, not repeated; manifold edges and vertices;
    /// orientation), then [`MeshError::ZeroAreaFace`] for a zero vector area and
    /// [`MeshError::PolygonFolds`]. Unreferenced vertices are dropped and reported, as for
    /// triangles; the angle range is that of the polygons' corner angles.
    pub fn validated(
        positions: Vec<[f64; 3]>,
        faces: FaceList,
    ) -> Result<(SurfaceMesh, ValidationReport), MeshError> {
        if let Some(triangles) = faces.to_triangles() {
            let (mesh, report) = TriangleMesh::validated(positions, triangles)?;
            return Ok((Self::Triangles(mesh), report));
        }
        check_combinatorics(&positions, &faces)?;
        check_polygon_geometry(&positions, &faces)?;
        let non_convex = non_convex_polygons(&positions, &faces);
        let kept = KeptVertices::of(&positions, &faces);
        let faces = faces.renumbered(&kept.new_index);
        let (positions, mut report) = kept.into_report(positions);
        let mesh = PolygonMesh::new(positions, faces)?;
        let (min, max, small) = polygon_angle_range(&mesh);
        report.min_angle_deg = min;
        report.max_angle_deg = max;
        let mesh = Self::Polygons(mesh);
        if let Some(warning) = mesh.inward_components() {
            report.warnings.push(warning);
        }
        if small > 0 {
            report
                .warnings
                .push(ValidationWarning::SmallAngles { faces: small });
        }
        if let Some((count, first_face)) = non_convex {
            report.warnings.push(ValidationWarning::NonConvexPolygons {
                count,
                first_face,
                first_line: None,
            });
        }
        Ok((mesh, report))
    }

    /// The mesh as a triangle mesh, if every face is a triangle.
    pub fn as_triangles(&self) -> Option<&TriangleMesh> {
        match self {
            Self::Triangles(mesh) => Some(mesh),
            Self::Polygons(_) => None,
        }
    }

    /// The triangle mesh, if every face is a triangle (the mesh itself back otherwise).
    #[allow(clippy::result_large_err)] // The error is the mesh itself, handed back whole.
    pub fn into_triangles(self) -> Result<TriangleMesh, Self> {
        match self {
            Self::Triangles(mesh) => Ok(mesh),
            polygons => Err(polygons),
        }
    }

    /// The mesh as a polygon mesh, if some face is not a triangle.
    pub fn as_polygons(&self) -> Option<&PolygonMesh> {
        match self {
            Self::Triangles(_) => None,
            Self::Polygons(mesh) => Some(mesh),
        }
    }

    /// The mesh with every polygon split into triangles by its own corners, for the entries
    /// that need triangles (`tvf triangulate`, `--triangulate`): no vertex is added or moved, so
    /// vertex numbers, positions and per-vertex data carry over. A polygon of `n` corners becomes
    /// the `n − 2` triangles of an ear clipping of its corners seen along its vector area (for a
    /// convex polygon any such split; for a non-convex one, triangles that stay inside it), each
    /// oriented like the polygon; triangles are listed face by face, a triangle face as itself.
    /// A triangle mesh comes back unchanged.
    ///
    /// Unlike the [`SurfaceMesh::display`] triangulation (a fan around the corner average, a new
    /// vertex per polygon) this is a mesh of the same vertices, which a triangle discretization
    /// can be built on and whose vertex fields compare with the polygon mesh's. Fails with
    /// [`MeshError::PolygonNotTriangulable`] on a polygon that folds over itself (the validation
    /// of [`SurfaceMesh::validated`] already refuses those).
    pub fn triangulated(&self) -> Result<TriangleMesh, MeshError> {
        match self {
            Self::Triangles(mesh) => Ok(mesh.clone()),
            Self::Polygons(mesh) => {
                let triangles = triangulate_by_corners(mesh.positions(), mesh.faces())?;
                TriangleMesh::new(mesh.positions().to_vec(), triangles)
            }
        }
    }

    /// Whether every face is a triangle.
    pub fn is_triangle_mesh(&self) -> bool {
        matches!(self, Self::Triangles(_))
    }

    /// `triangles` or `polygons`, for messages and file headers.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Self::Triangles(_) => "triangles",
            Self::Polygons(_) => "polygons",
        }
    }

    /// The topology: edges `(a, b)`, `a < b`, in lexicographic order, their faces, components,
    /// boundary loops, genus.
    pub fn topology(&self) -> &MeshTopology {
        match self {
            Self::Triangles(mesh) => mesh.topology(),
            Self::Polygons(mesh) => mesh.topology(),
        }
    }

    /// Number of vertices `V`.
    pub fn vertex_count(&self) -> usize {
        self.positions().len()
    }

    /// Number of edges `E`.
    pub fn edge_count(&self) -> usize {
        self.topology().edges().len()
    }

    /// Number of faces `F`.
    pub fn face_count(&self) -> usize {
        match self {
            Self::Triangles(mesh) => mesh.face_count(),
            Self::Polygons(mesh) => mesh.face_count(),
        }
    }

    /// Vertex positions, `V` entries.
    pub fn positions(&self) -> &[[f64; 3]] {
        match self {
            Self::Triangles(mesh) => mesh.positions(),
            Self::Polygons(mesh) => mesh.positions(),
        }
    }

    /// Edges `(a, b)`, `a < b`, in lexicographic order.
    pub fn edges(&self) -> &[[usize; 2]] {
        self.topology().edges()
    }

    /// The corners of face `f`, counter-clockwise.
    pub fn face(&self, f: usize) -> &[usize] {
        match self {
            Self::Triangles(mesh) => &mesh.faces()[f],
            Self::Polygons(mesh) => mesh.face(f),
        }
    }

    /// The faces as corner lists.
    pub fn faces(&self) -> &dyn FaceCorners {
        match self {
            Self::Triangles(mesh) => Mesh::face_corners(mesh),
            Self::Polygons(mesh) => mesh.faces(),
        }
    }

    /// A copy of the faces as one flat list.
    pub fn to_face_list(&self) -> FaceList {
        match self {
            Self::Triangles(mesh) => FaceList::from_triangles(mesh.faces()),
            Self::Polygons(mesh) => mesh.faces().clone(),
        }
    }

    /// The signed volume enclosed (units of length³): `Σ_f ⟨m_f, a_f⟩/3` over the faces'
    /// corner averages and vector areas (for a triangle mesh, [`TriangleMesh::signed_volume`]);
    /// positive for a closed mesh with outward normals.
    pub fn signed_volume(&self) -> f64 {
        match self {
            Self::Triangles(mesh) => mesh.signed_volume(),
            Self::Polygons(_) => (0..self.face_count())
                .map(|f| dot(self.face_centroid(f), self.vector_area(f)) / 3.0)
                .sum(),
        }
    }

    /// Number of corners of face `f`.
    pub fn face_size(&self, f: usize) -> usize {
        self.face(f).len()
    }

    /// How many faces have each number of corners: `(size, count)` pairs, sizes ascending
    /// (`[(3, F)]` for a triangle mesh, `[(4, 96)]` for a cube-sphere of 96 quads).
    pub fn face_size_counts(&self) -> Vec<(usize, usize)> {
        let mut counts = std::collections::BTreeMap::new();
        for f in 0..self.face_count() {
            *counts.entry(self.face_size(f)).or_insert(0) += 1;
        }
        counts.into_iter().collect()
    }

    /// The edge joining corner `c` of face `f` to corner `c + 1` (cyclically).
    pub fn face_edge(&self, f: usize, c: usize) -> usize {
        match self {
            // A triangle's `face_edges[t][k]` is the edge opposite corner `k`: the edge from
            // corner `c` is opposite corner `c + 2`.
            Self::Triangles(mesh) => mesh.face_edges()[f][(c + 2) % 3],
            Self::Polygons(mesh) => mesh.face_edge(f, c),
        }
    }

    /// The vector area of face `f` (`½ Σ_c p_c × p_{c+1}`, units of length²): its direction is
    /// the face normal, its length the face area.
    pub fn vector_area(&self, f: usize) -> [f64; 3] {
        match self {
            Self::Triangles(mesh) => scale(mesh.face_normal_scaled(f), 0.5),
            Self::Polygons(mesh) => mesh.vector_area(f),
        }
    }

    /// The area of face `f` (for a polygon the length of its vector area; units of length²).
    pub fn face_area(&self, f: usize) -> f64 {
        match self {
            Self::Triangles(mesh) => mesh.face_area(f),
            Self::Polygons(mesh) => mesh.face_area(f),
        }
    }

    /// Areas of all faces, `F` entries.
    pub fn face_areas(&self) -> Vec<f64> {
        (0..self.face_count()).map(|f| self.face_area(f)).collect()
    }

    /// Total surface area.
    pub fn total_area(&self) -> f64 {
        self.face_areas().iter().sum()
    }

    /// Unit normal of face `f` (for a polygon, along its vector area).
    pub fn face_normal(&self, f: usize) -> [f64; 3] {
        match self {
            Self::Triangles(mesh) => mesh.face_normal(f),
            Self::Polygons(mesh) => mesh.face_normal(f),
        }
    }

    /// The average of the corners of face `f` (`(p_0 + … + p_{n−1}) / n`).
    pub fn face_centroid(&self, f: usize) -> [f64; 3] {
        let corners = self.face(f);
        let n = corners.len() as f64;
        std::array::from_fn(|k| corners.iter().map(|&v| self.positions()[v][k]).sum::<f64>() / n)
    }

    /// Whether the mesh has no boundary edge.
    pub fn is_closed(&self) -> bool {
        self.topology().is_closed()
    }

    /// Whether edge `e` has only one face.
    pub fn is_boundary_edge(&self, e: usize) -> bool {
        self.topology().is_boundary_edge(e)
    }

    /// Number of edge-connected components.
    pub fn component_count(&self) -> usize {
        self.topology().component_count()
    }

    /// Component id of every face.
    pub fn face_components(&self) -> &[usize] {
        self.topology().face_components()
    }

    /// Component id of every vertex (`usize::MAX` for a vertex no face uses).
    pub fn vertex_components(&self) -> Vec<usize> {
        self.topology().vertex_components(self.faces())
    }

    /// Boundary loops as closed vertex cycles (the surface on the left).
    pub fn boundary_loops(&self) -> Vec<Vec<usize>> {
        self.topology().boundary_loops()
    }

    /// Genus of every component.
    pub fn component_genera(&self) -> Vec<usize> {
        self.topology().component_genera(self.faces())
    }

    /// Euler characteristic `V − E + F` over referenced vertices.
    pub fn euler_characteristic(&self) -> i64 {
        self.topology()
            .component_euler_characteristics(self.faces())
            .iter()
            .sum()
    }

    /// Total genus, summed over components.
    pub fn genus(&self) -> usize {
        self.component_genera().iter().sum()
    }

    /// A 64-bit hash of the vertex coordinates and the faces (order included). For a triangle
    /// mesh it is [`TriangleMesh::fingerprint`]; a polygon mesh hashes its face sizes too, so
    /// it never matches a triangle mesh.
    pub fn fingerprint(&self) -> u64 {
        match self {
            Self::Triangles(mesh) => mesh.fingerprint(),
            Self::Polygons(mesh) => mesh.fingerprint(),
        }
    }

    /// The triangles the mesh is drawn with: the mesh itself for a triangle mesh, else its
    /// [`super::DisplayTriangulation`].
    pub fn display(&self) -> &TriangleMesh {
        match self {
            Self::Triangles(mesh) => mesh,
            Self::Polygons(mesh) => mesh.display_mesh(),
        }
    }

    /// The face of the mesh that display triangle `t` belongs to.
    pub fn display_face(&self, t: usize) -> usize {
        match self {
            Self::Triangles(_) => t,
            Self::Polygons(mesh) => mesh.display().face_of(t),
        }
    }

    /// The surface point at barycentric coordinates `b` of display triangle `t`.
    pub fn display_point(&self, t: usize, b: [f64; 3]) -> SurfacePoint {
        match self {
            Self::Triangles(_) => SurfacePoint::barycentric(t, b),
            Self::Polygons(mesh) => {
                let face = mesh.display().face_of(t);
                let weights = mesh.display().corner_weights(t, b, mesh.face(face).len());
                SurfacePoint { face, weights }
            }
        }
    }

    /// Per-face values repeated on every display triangle of their face (`F` entries in, one
    /// per display triangle out).
    pub fn on_display<T: Clone>(&self, per_face: &[T]) -> Vec<T> {
        match self {
            Self::Triangles(_) => per_face.to_vec(),
            Self::Polygons(mesh) => mesh
                .display()
                .faces_of_triangles()
                .iter()
                .map(|&f| per_face[f].clone())
                .collect(),
        }
    }

    /// The corner average of face `f` as a surface point.
    pub fn centroid_point(&self, f: usize) -> SurfacePoint {
        SurfacePoint::centroid(f, self.face_size(f))
    }

    /// Checks that `point` is a point of this mesh: its face exists, it has one weight per corner,
    /// and the weights are finite, non-negative and sum to 1 (to [`POINT_WEIGHT_TOLERANCE`]).
    pub fn check_point(&self, point: &SurfacePoint) -> Result<(), SurfacePointError> {
        let face = point.face;
        if face >= self.face_count() {
            return Err(SurfacePointError::FaceOutOfRange {
                face,
                face_count: self.face_count(),
            });
        }
        let corners = self.face_size(face);
        if point.weights.len() != corners {
            return Err(SurfacePointError::WrongWeightCount {
                face,
                corners,
                weights: point.weights.len(),
            });
        }
        let convex = point.weights.iter().all(|w| w.is_finite() && *w >= 0.0)
            && (point.weights.iter().sum::<f64>() - 1.0).abs() <= POINT_WEIGHT_TOLERANCE;
        if !convex {
            return Err(SurfacePointError::NotConvex {
                face,
                weights: point.weights.clone(),
            });
        }
        Ok(())
    }

    /// The position `Σ_c w_c p_c` of a point of this mesh (checked with
    /// [`SurfaceMesh::check_point`]).
    pub fn point_position(&self, point: &SurfacePoint) -> [f64; 3] {
        let mut p = [0.0; 3];
        for (&v, &w) in self.face(point.face).iter().zip(&point.weights) {
            for (k, x) in p.iter_mut().enumerate() {
                *x += w * self.positions()[v][k];
            }
        }
        p
    }

    /// The closed components whose signed volume (`Σ_f ⟨m_f, a_f⟩/3` over the faces' centroids
    /// and vector areas) is negative: their normals point inward.
    fn inward_components(&self) -> Option<ValidationWarning> {
        let count = self.component_count();
        let mut volume = vec![0.0; count];
        let mut first_face = vec![usize::MAX; count];
        for (f, &c) in self.face_components().iter().enumerate() {
            volume[c] += dot(self.face_centroid(f), self.vector_area(f)) / 3.0;
            first_face[c] = first_face[c].min(f);
        }
        inward_normals_warning(
            &volume,
            &first_face,
            &self.vertex_components(),
            &self.boundary_loops(),
        )
    }
}

/// The smallest and largest corner angle (degrees) over all faces of `mesh`, and how many faces
/// have a corner below [`SMALL_ANGLE_DEG`]. The angle at corner `c` is between the sides to
/// corners `c − 1` and `c + 1` (for a non-convex planar polygon, the smaller of the two angles
/// there).
fn polygon_angle_range(mesh: &PolygonMesh) -> (f64, f64, usize) {
    let (mut min, mut max, mut small) = (f64::INFINITY, 0.0f64, 0);
    for f in 0..mesh.face_count() {
        let p = mesh.corner_positions(f);
        let n = p.len();
        let mut has_small = false;
        for c in 0..n {
            let (u, v) = (sub(p[(c + n - 1) % n], p[c]), sub(p[(c + 1) % n], p[c]));
            let angle = (dot(u, v) / (norm(u) * norm(v)))
                .clamp(-1.0, 1.0)
                .acos()
                .to_degrees();
            min = min.min(angle);
            max = max.max(angle);
            has_small |= angle < SMALL_ANGLE_DEG;
        }
        small += usize::from(has_small);
    }
    (min, max, small)
}

impl Mesh for SurfaceMesh {
    fn positions(&self) -> &[[f64; 3]] {
        SurfaceMesh::positions(self)
    }

    fn face_corners(&self) -> &dyn FaceCorners {
        SurfaceMesh::faces(self)
    }

    fn face_edge(&self, f: usize, c: usize) -> usize {
        SurfaceMesh::face_edge(self, f, c)
    }

    fn topology(&self) -> &MeshTopology {
        SurfaceMesh::topology(self)
    }

    fn as_triangles(&self) -> Option<&TriangleMesh> {
        SurfaceMesh::as_triangles(self)
    }

    fn fingerprint(&self) -> u64 {
        SurfaceMesh::fingerprint(self)
    }
}
