//! `tvf.Complex`: a discretization built on a mesh — an entry of the catalog, or five matrices a
//! researcher assembled (`Complex.from_matrices`), behind the same seam.

use crate::arrays::{csr_from_parts, CsrParts};
use crate::basis_parts::{spectral_basis, BasisParts};
use crate::errors::{from_error, tvf_error};
use crate::masses::{
    direct_co_potential_mass, mass_description, mass_from_input, Given, MassInput,
};
use crate::mesh::Mesh;
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tvf_core::discretization::{BoundaryCondition, HodgeComplex, HodgeOperators, NodeKind};
use tvf_core::SurfaceMesh;
use tvf_discretizations::{
    builtin_catalog, catalog_entry, default_discretization, parse_intrinsic_delaunay,
    polygon_dec_entry, polygon_dec_id, split_intrinsic_id, BoxedComplex, ComplexMatrices,
    FixedNodes, MatrixComplex, MatrixSampling, StatedNodeKinds, DEFAULT_STABILISATION,
};
use tvf_spectral::SpectralBasis;

/// A complex and the mesh it was built on.
#[pyclass(frozen, module = "tvf._native")]
pub struct Complex {
    pub complex: BoxedComplex,
    pub mesh: SurfaceMesh,
    pub label: String,
}

#[pymethods]
impl Complex {
    /// Catalog entry `discretization` on `mesh` with boundary condition `boundary`
    /// (`tangential` or `normal`; only matters on meshes with boundary). Without a
    /// `discretization`, the default of the mesh's kind (`conforming-barycentric` on triangles,
    /// `polygon-dec` on polygons). `beta` is polygon-dec's stabilisation weight (its default is
    /// 1); giving it with another entry is an error.
    /// `intrinsic` (`flip` or `refine`) builds the entry on the intrinsic Delaunay
    /// triangulation of the mesh, as an id ending in `+intrinsic-delaunay` (or `…-refine`) does.
    #[staticmethod]
    #[pyo3(signature = (mesh, discretization, boundary, beta = None, intrinsic = None))]
    fn build(
        py: Python<'_>,
        mesh: &Mesh,
        discretization: Option<&str>,
        boundary: &str,
        beta: Option<f64>,
        intrinsic: Option<&str>,
    ) -> PyResult<Self> {
        let discretization = discretization.unwrap_or_else(|| default_discretization(&mesh.mesh));
        let (discretization, named_mode) = split_intrinsic_id(discretization);
        let mode = match intrinsic {
            Some(name) => Some(parse_intrinsic_delaunay(name).map_err(tvf_error)?),
            None => named_mode,
        };
        let stabilised;
        let entry = match beta {
            None => catalog_entry(discretization).map_err(|e| from_error(&e))?,
            Some(beta) if discretization == polygon_dec_id(DEFAULT_STABILISATION) => {
                if !(beta.is_finite() && beta > 0.0) {
                    return Err(tvf_error(format!(
                        "beta = {beta}: polygon-dec's stabilisation weight must be a positive number"
                    )));
                }
                stabilised = polygon_dec_entry(beta);
                &stabilised
            }
            Some(_) => {
                return Err(tvf_error(format!(
                    "beta is the stabilisation weight of polygon-dec; '{discretization}' has none"
                )))
            }
        };
        let modified = mode.map(|mode| entry.on_intrinsic_delaunay(mode));
        let entry = modified.as_ref().unwrap_or(entry);
        let discretization = entry.id();
        let condition = BoundaryCondition::from_name(boundary).ok_or_else(|| {
            tvf_error(format!(
                "'{boundary}' is not a boundary condition: tangential or normal"
            ))
        })?;
        let complex = py
            .detach(|| entry.build_with(&mesh.mesh, condition))
            .map_err(|e| {
                tvf_error(format!(
                    "{}: cannot build the discretization '{discretization}' (needs: {}): {e}",
                    mesh.label,
                    entry.preconditions()
                ))
            })?;
        Ok(Self {
            complex,
            mesh: mesh.mesh.clone(),
            label: mesh.label.clone(),
        })
    }

    /// A complex from the five matrices on a closed `mesh`: the CSR parts of `d0`, `d1`; the
    /// masses `M0`, `M1` and either `M2` or its inverse `m2_inverse` (exactly one of them), each
    /// a diagonal or CSR parts (see [`MassInput`]); `sampling` is `none`, `face-frames`,
    /// `whitney` or `polygon-sharp`; `nodes` the node kinds of the three spaces, where stated
    /// (`vertices`, `edges`, `faces`, `face-frames`; the others from their sizes). Errors name
    /// the matrix: shapes, finite entries, symmetry, positive definiteness on the used nodes (a
    /// Cholesky factorization of each sparse mass), `d1 · d0 = 0`; a size two node kinds share
    /// with no kind stated.
    ///
    /// `fixed` (potentials, fields, co-potentials: the node indices the boundary condition fixes
    /// to zero) and `boundary` (`tangential` or `normal`, recorded in the id and topology) as
    /// the folder format's `fixed_nodes` and `boundary_condition`; both `None` on a closed mesh.
    #[staticmethod]
    #[pyo3(signature = (mesh, d0, d1, m0, m1, m2, m2_inverse, sampling, id, nodes = None, fixed = None, boundary = None))]
    #[allow(clippy::too_many_arguments)]
    fn from_matrices(
        py: Python<'_>,
        mesh: &Mesh,
        d0: CsrParts<'_>,
        d1: CsrParts<'_>,
        m0: MassInput<'_>,
        m1: MassInput<'_>,
        m2: Option<MassInput<'_>>,
        m2_inverse: Option<MassInput<'_>>,
        sampling: &str,
        id: &str,
        nodes: Option<StatedNodeNames>,
        fixed: Option<(Vec<usize>, Vec<usize>, Vec<usize>)>,
        boundary: Option<&str>,
    ) -> PyResult<Self> {
        let stated = stated_node_kinds(nodes)?;
        let sampling = MatrixSampling::from_name(sampling).ok_or_else(|| {
            tvf_error(format!(
                "'{sampling}' is not a sampling: none, face-frames, whitney or polygon-sharp"
            ))
        })?;
        let labelled = |e: PyErr| tvf_error(format!("{}: {}", mesh.label, e.value(py)));
        let d0 = csr_from_parts("d0", d0).map_err(labelled)?;
        let d1 = csr_from_parts("d1", d1).map_err(labelled)?;
        let m0 = mass_from_input("M0", m0, Given::Mass).map_err(labelled)?;
        let m1 = mass_from_input("M1", m1, Given::Mass).map_err(labelled)?;
        let m2 = match (m2, m2_inverse) {
            (Some(m2), None) => {
                mass_from_input("M2", m2, Given::Mass).and_then(direct_co_potential_mass)
            }
            (None, Some(inverse)) => mass_from_input("M2_inverse (M2⁻¹)", inverse, Given::Inverse),
            _ => Err(tvf_error(
                "give the co-potential mass either as M2 or as its inverse M2_inverse, not both",
            )),
        }
        .map_err(labelled)?;
        let condition = match boundary {
            None => BoundaryCondition::default(),
            Some(name) => BoundaryCondition::from_name(name).ok_or_else(|| {
                tvf_error(format!("boundary_condition '{name}': tangential or normal"))
            })?,
        };
        let matrices = ComplexMatrices { d0, d1, m0, m1, m2 };
        let complex = py
            .detach(|| match (fixed, boundary) {
                (None, None) => {
                    MatrixComplex::with_node_kinds(id, &mesh.mesh, matrices, &stated, sampling)
                }
                (fixed, _) => {
                    let (potentials, fields, co_potentials) = fixed.unwrap_or_default();
                    let fixed = FixedNodes {
                        potentials,
                        fields,
                        co_potentials,
                    };
                    // As a folder's id: the condition named where the mesh has a boundary.
                    let id = match mesh.mesh.is_closed() {
                        true => id.to_string(),
                        false => format!("{id}+{}", condition.name()),
                    };
                    MatrixComplex::with_boundary(
                        &id, &mesh.mesh, matrices, &stated, &fixed, condition, sampling,
                    )
                }
            })
            .map_err(|e| tvf_error(format!("{}: {e}", mesh.label)))?;
        Ok(Self {
            complex: Box::new(complex),
            mesh: mesh.mesh.clone(),
            label: mesh.label.clone(),
        })
    }

    /// The complex's id (catalog id, with `+tangential`/`+normal` on meshes with boundary).
    #[getter]
    fn id(&self) -> String {
        self.complex.id().to_string()
    }

    /// `(n0, n1, n2)`: potentials, field coefficients, co-potentials.
    #[getter]
    fn dimensions(&self) -> (usize, usize, usize) {
        (
            self.complex.potential_dimension(),
            self.complex.field_dimension(),
            self.complex.co_potential_dimension(),
        )
    }

    /// Node kinds of the three spaces (`vertices`, `edges`, `faces`, `face-frames`).
    #[getter]
    fn node_kinds(&self) -> (String, String, String) {
        (
            self.complex.potential_nodes().kind.name().to_string(),
            self.complex.field_nodes().kind.name().to_string(),
            self.complex.co_potential_nodes().kind.name().to_string(),
        )
    }

    /// Dimension of the harmonic space.
    #[getter]
    fn harmonic_dimension(&self) -> usize {
        self.complex.topology().harmonic_dimension
    }

    /// Whether fields can be sampled as 3D vectors (face vectors in and out).
    #[getter]
    fn has_sampling(&self) -> bool {
        self.complex.sampling().is_some()
    }

    /// How the complex stores each mass: `{"M0": {"storage", "form", "key"}, ...}` (see
    /// [`mass_description`]).
    #[getter]
    fn masses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        mass_description(py, self.complex.as_ref())
    }

    fn __repr__(&self) -> String {
        let (n0, n1, n2) = self.dimensions();
        format!(
            "Complex('{}' on '{}': n0={n0}, n1={n1}, n2={n2})",
            self.complex.id(),
            self.label
        )
    }
}

/// The node kinds `from_matrices` is given: one name or `None` per space.
type StatedNodeNames = (Option<String>, Option<String>, Option<String>);

/// The [`StatedNodeKinds`] named by `nodes` (none stated without it).
fn stated_node_kinds(nodes: Option<StatedNodeNames>) -> PyResult<StatedNodeKinds> {
    let Some((potentials, fields, co_potentials)) = nodes else {
        return Ok([None; 3]);
    };
    let kind = |name: Option<String>| -> PyResult<Option<NodeKind>> {
        name.map(|name| {
            NodeKind::from_name(&name).ok_or_else(|| {
                tvf_error(format!(
                    "nodes: '{name}' is not a node kind: vertices, edges, faces or face-frames"
                ))
            })
        })
        .transpose()
    };
    Ok([kind(potentials)?, kind(fields)?, kind(co_potentials)?])
}

/// The built-in catalog: one dict per entry (`id`, `description`, `preconditions`, `needs_delaunay`,
/// `boundary_conditions`).
#[pyfunction]
pub fn discretizations(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    builtin_catalog()
        .iter()
        .map(|entry| {
            let d = PyDict::new(py);
            d.set_item("id", entry.id())?;
            d.set_item("description", entry.description())?;
            d.set_item("preconditions", entry.preconditions())?;
            d.set_item("needs_delaunay", entry.needs_delaunay())?;
            d.set_item("builds_on_intrinsic", entry.builds_on_intrinsic())?;
            let conditions: Vec<&str> = entry
                .boundary_conditions()
                .iter()
                .map(|b| b.name())
                .collect();
            d.set_item("boundary_conditions", conditions)?;
            Ok(d)
        })
        .collect()
}

/// A field's coefficients for `complex`, checked: length `n1`, finite.
pub fn checked_field(
    complex: &dyn HodgeComplex,
    field: &PyReadonlyArray1<'_, f64>,
) -> PyResult<Vec<f64>> {
    let values = field.as_slice()?.to_vec();
    if values.len() != complex.field_dimension() {
        return Err(tvf_error(format!(
            "field: expected {} coefficients for '{}', got {}",
            complex.field_dimension(),
            complex.id(),
            values.len()
        )));
    }
    if let Some(i) = values.iter().position(|x| !x.is_finite()) {
        return Err(tvf_error(format!(
            "field: non-finite value at coefficient {i}"
        )));
    }
    Ok(values)
}

/// What the field functions check before they run.
impl Complex {
    /// A field's coefficients, checked: length `n1`, finite.
    pub fn field(&self, field: &PyReadonlyArray1<'_, f64>) -> PyResult<Vec<f64>> {
        checked_field(self.complex.as_ref(), field)
    }

    /// A basis given as Python's arrays, checked against this complex.
    pub fn basis(
        &self,
        (eigenvalues, families, coefficients): BasisParts<'_>,
    ) -> PyResult<SpectralBasis> {
        spectral_basis(self.complex.as_ref(), eigenvalues, families, coefficients)
    }
}
