//! `tvf.Mesh`: a validated triangle or polygon mesh, from arrays or a file, with the map back to the input's
//! vertex numbers.

use crate::arrays::vectors_to_numpy;
use crate::errors::{from_error, tvf_error};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use tvf_core::io::load_mesh;
use tvf_core::mesh::ValidationReport;
use tvf_core::{FaceList, SurfaceMesh};

/// A valid oriented manifold triangle or polygon mesh (see `tvf.Mesh` in Python for the documentation).
#[pyclass(frozen, module = "tvf._native")]
pub struct Mesh {
    pub mesh: SurfaceMesh,
    pub report: ValidationReport,
    pub label: String,
}

#[pymethods]
impl Mesh {
    /// Validates `positions` (`n × 3` float64) and faces given as `corners` (every face's
    /// 0-based vertex indices, one face after the other, int64) and `sizes` (the number of
    /// corners of each face, int64) like the command line's mesh readers; `label` names the mesh
    /// in error messages. Faces of three corners only make a triangle mesh, others a polygon
    /// mesh.
    #[new]
    #[pyo3(signature = (positions, corners, sizes, label = "mesh".to_string()))]
    fn new(
        py: Python<'_>,
        positions: PyReadonlyArray2<'_, f64>,
        corners: PyReadonlyArray1<'_, i64>,
        sizes: PyReadonlyArray1<'_, i64>,
        label: String,
    ) -> PyResult<Self> {
        let positions: Vec<[f64; 3]> = rows(&positions.as_array(), "V")?;
        let (corners, sizes) = (corners.as_array(), sizes.as_array());
        let mut faces = FaceList::new();
        let mut start = 0usize;
        let mut face = Vec::new();
        for (t, &size) in sizes.iter().enumerate() {
            let end = usize::try_from(size)
                .ok()
                .and_then(|n| start.checked_add(n))
                .filter(|&end| end <= corners.len())
                .ok_or_else(|| {
                    tvf_error(format!(
                        "{label}: face {t}: {size} corners do not fit the {} corner indices given",
                        corners.len()
                    ))
                })?;
            face.clear();
            for &v in corners.iter().skip(start).take(end - start) {
                face.push(
                    usize::try_from(v)
                        .ok()
                        .filter(|&v| v < positions.len())
                        .ok_or_else(|| {
                            // Worded as the mesh readers word it (`tvf info mesh.off`).
                            tvf_error(format!(
                                "{label}: face {t}: vertex index {v} is out of range: the mesh has {} vertices",
                                positions.len()
                            ))
                        })?,
                );
            }
            faces.push(&face);
            start = end;
        }
        if start != corners.len() {
            return Err(tvf_error(format!(
                "{label}: the face sizes add up to {start} corners, but {} corner indices were given",
                corners.len()
            )));
        }
        let (mesh, report) = py
            .detach(|| SurfaceMesh::validated(positions, faces))
            .map_err(|e| tvf_error(format!("{label}: {e}")))?;
        check_geometry_range(&mesh, &label)?;
        Ok(Self {
            mesh,
            report,
            label,
        })
    }

    /// Vertex positions, `V × 3` (unreferenced input vertices dropped).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        vectors_to_numpy(py, self.mesh.positions())
    }

    /// Faces, counter-clockwise seen from outside, 0-based indices into `positions`: an `F × 3`
    /// int64 array for a triangle mesh, a list of `F` int64 arrays (one per polygon) otherwise.
    #[getter]
    fn faces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match &self.mesh {
            SurfaceMesh::Triangles(mesh) => {
                let faces = mesh.faces();
                Ok(
                    Array2::from_shape_fn((faces.len(), 3), |(t, c)| faces[t][c] as i64)
                        .into_pyarray(py)
                        .into_any(),
                )
            }
            SurfaceMesh::Polygons(mesh) => {
                let polygons: Vec<Vec<i64>> = mesh
                    .faces()
                    .iter()
                    .map(|f| f.iter().map(|&v| v as i64).collect())
                    .collect();
                Ok(pyo3::types::PyList::new(py, polygons)?.into_any())
            }
        }
    }

    /// Edges, `E × 2` int64, `(a, b)` with `a < b`, in lexicographic order.
    #[getter]
    fn edges<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        let edges = self.mesh.edges();
        Array2::from_shape_fn((edges.len(), 2), |(e, c)| edges[e][c] as i64)
            .into_pyarray(py)
            .into_any()
    }

    /// `vertex_map[v]`: the input index of mesh vertex `v` (`V` entries, int64).
    #[getter]
    fn vertex_map<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        let map: Vec<i64> = self
            .report
            .original_vertex
            .iter()
            .map(|&v| v as i64)
            .collect();
        map.into_pyarray(py).into_any()
    }

    /// Number of input vertices, referenced or not.
    #[getter]
    fn input_vertex_count(&self) -> usize {
        self.report.input_vertex_count
    }

    /// Validation warnings, one sentence each.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.report.warnings.iter().map(|w| w.to_string()).collect()
    }

    /// The label used in messages (the file path, or the label given).
    #[getter]
    fn label(&self) -> String {
        self.label.clone()
    }

    /// `(V, E, F)`: the numbers of vertices, edges and faces (the sizes a matrix of the mesh
    /// may have, with `2F`).
    #[getter]
    fn sizes(&self) -> (usize, usize, usize) {
        (
            self.mesh.vertex_count(),
            self.mesh.edge_count(),
            self.mesh.face_count(),
        )
    }

    /// Genus summed over the connected components.
    #[getter]
    fn genus(&self) -> usize {
        self.mesh.genus()
    }

    /// Number of connected components.
    #[getter]
    fn component_count(&self) -> usize {
        self.mesh.component_count()
    }

    /// Whether the mesh has no boundary edge.
    #[getter]
    fn is_closed(&self) -> bool {
        self.mesh.is_closed()
    }

    /// Number of boundary loops.
    #[getter]
    fn boundary_loop_count(&self) -> usize {
        self.mesh.boundary_loops().len()
    }

    /// Area of every face, `F` entries.
    #[getter]
    fn face_areas<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.mesh.face_areas().into_pyarray(py).into_any()
    }

    /// Unit normal of every face, `F × 3`, `(p1 − p0) × (p2 − p0)` normalised.
    #[getter]
    fn face_normals<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        let normals: Vec<[f64; 3]> = (0..self.mesh.face_count())
            .map(|t| self.mesh.face_normal(t))
            .collect();
        vectors_to_numpy(py, &normals)
    }

    /// The 16-hex-digit fingerprint constraint files and compressed files are stamped with.
    #[getter]
    fn fingerprint(&self) -> String {
        format!("{:016x}", self.mesh.fingerprint())
    }

    fn __repr__(&self) -> String {
        format!(
            "Mesh('{}': V={}, E={}, F={}, genus {}, {})",
            self.label,
            self.mesh.vertex_count(),
            self.mesh.edge_count(),
            self.mesh.face_count(),
            self.mesh.genus(),
            if self.mesh.is_closed() {
                "closed"
            } else {
                "with boundary"
            }
        )
    }
}

/// Reads and validates a mesh file (OBJ, OFF, PLY); errors name the file and the line.
#[pyfunction]
pub fn read_mesh(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Mesh> {
    let loaded = py.detach(|| load_mesh(&path)).map_err(|e| from_error(&e))?;
    let label = path.display().to_string();
    check_geometry_range(&loaded.mesh, &label)?;
    Ok(Mesh {
        mesh: loaded.mesh,
        report: loaded.report,
        label,
    })
}

/// Rows of an `n × 3` array; another shape is an error naming `what`.
fn rows<T: Copy>(array: &numpy::ndarray::ArrayView2<'_, T>, what: &str) -> PyResult<Vec<[T; 3]>> {
    if array.ncols() != 3 {
        return Err(tvf_error(format!(
            "{what}: expected shape (n, 3), got {:?}",
            array.shape()
        )));
    }
    Ok(array
        .rows()
        .into_iter()
        .map(|r| [r[0], r[1], r[2]])
        .collect())
}

/// The command line's refusal of meshes whose area overflows `f64`
/// ([`SurfaceMesh::check_geometry_range`]), naming the mesh.
fn check_geometry_range(mesh: &SurfaceMesh, label: &str) -> PyResult<()> {
    mesh.check_geometry_range()
        .map_err(|e| tvf_error(format!("{label}: {e}")))
}
