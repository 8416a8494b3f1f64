//! `tvf.BasisFile`'s native half: a `.tvfb` file written by `tvf basis`, read as the command
//! line reads `--basis` files. [`basis_file_summary`] reads its header, eigenvalues and families
//! without its fields; [`BasisBlocks`] is the file checked whole for one mesh (key, matrices,
//! size, payload checksum, finite values: everything `tvf filter --basis` checks) and then used
//! a block of stored columns at a time ([`BasisFileBlocks`]): projections, filters and
//! syntheses hold one block (at most `block_bytes`), never the `n1 × d` fields. Every pass over
//! the file (the check at opening included) reports each block to the call's optional
//! `progress(stage, done, wanted)` callable (bytes of the pass) and polls Ctrl+C there
//! ([`block_observer`]), so that `KeyboardInterrupt` stops the pass at once.

use crate::arrays::{checked_rows, face_fields_to_numpy};
use crate::basis::basis_dict;
use crate::block_observer::block_observer;
use crate::complex::checked_field;
use crate::design::{constraints_on, result, solve_reduced};
use crate::errors::{from_error, tvf_error, with_context};
use crate::fields::{compress_rows, decompress_rows, face_vectors_in, face_vectors_out};
use crate::interrupt::{detached, interruptible, Interruption};
use crate::mesh::Mesh;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use std::path::PathBuf;
use std::sync::Arc;
use tvf_core::discretization::{BoundaryCondition, HodgeOperators, MatrixHash};
use tvf_core::SurfaceMesh;
use tvf_design::ReducedBasis;
use tvf_discretizations::builtin_catalog;
use tvf_spectral::{
    basis_file_complex, field_basis_id, load_basis, read_basis_spectrum, BasisFileBlocks,
    BasisFileKey, BasisFileLayout, FieldBasis, FourierAnalysis, FrequencyResponse,
    ObservedBasisFile, SpectralFilter,
};

/// What the basis file `path` says without its fields being read, as a dict: `version`,
/// `layout` (`eigenfunctions` or `fields`), `discretization` (the complex id), `mesh_fingerprint`
/// (16 hex digits), `face_count`, `field_dimension` (`n1`), `potential_dimension` and
/// `co_potential_dimension` (`n0`, `n2`; `None` in the fields layout), `eigenvalues` (`d`),
/// `families`, `counts` (per family), `matrix_hash` (hex per matrix; `None` before format
/// version 3), `file_bytes`. The file's size is checked against its header; its checksum is
/// checked when it is used on a mesh.
#[pyfunction]
pub fn basis_file_summary(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyDict>> {
    let spectrum = read_basis_spectrum(&path).map_err(|e| from_error(&e))?;
    let header = &spectrum.header;
    let out = PyDict::new(py);
    out.set_item("version", header.version)?;
    let (layout, dimensions) = match header.layout {
        BasisFileLayout::Fields => ("fields", None),
        BasisFileLayout::Eigenfunctions {
            potential_dimension,
            co_potential_dimension,
        } => (
            "eigenfunctions",
            Some((potential_dimension, co_potential_dimension)),
        ),
    };
    out.set_item("layout", layout)?;
    out.set_item("discretization", &header.key.discretization)?;
    out.set_item(
        "mesh_fingerprint",
        format!("{:016x}", header.key.mesh_fingerprint),
    )?;
    out.set_item("face_count", header.key.face_count)?;
    out.set_item("field_dimension", header.key.field_dimension)?;
    out.set_item("potential_dimension", dimensions.map(|d| d.0))?;
    out.set_item("co_potential_dimension", dimensions.map(|d| d.1))?;
    out.set_item("eigenvalues", spectrum.eigenvalues.clone().into_pyarray(py))?;
    let families: Vec<&str> = spectrum.families.iter().map(|f| f.name()).collect();
    out.set_item("families", families)?;
    let counts = PyDict::new(py);
    counts.set_item("harmonic", header.harmonic_count)?;
    counts.set_item("integrable", header.integrable_count)?;
    counts.set_item("cointegrable", header.cointegrable_count)?;
    out.set_item("counts", counts)?;
    let hash = match &header.key.matrix_hash {
        Some(hash) => Some(matrix_hash_dict(py, hash)?),
        None => None,
    };
    out.set_item("matrix_hash", hash)?;
    out.set_item("file_bytes", spectrum.file_bytes)?;
    Ok(out)
}

/// The hashes of a complex's matrices by name (`d0` … `fixed nodes`), 16 hex digits each.
fn matrix_hash_dict<'py>(py: Python<'py>, hash: &MatrixHash) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let parts = [hash.d0, hash.d1, hash.m0, hash.m1, hash.m2, hash.nodes];
    for (name, part) in MatrixHash::PART_NAMES.iter().zip(parts) {
        out.set_item(*name, format!("{part:016x}"))?;
    }
    Ok(out)
}

/// A basis file in the eigenfunctions layout (format version 3), checked for one mesh and read
/// in blocks.
#[pyclass(frozen, module = "tvf._native")]
pub struct BasisBlocks {
    blocks: Arc<BasisFileBlocks>,
    /// The mesh the file was checked against (constraints are compiled on it).
    mesh: SurfaceMesh,
    path: PathBuf,
    /// The mesh and complex the file was checked against.
    key: BasisFileKey,
}

#[pymethods]
impl BasisBlocks {
    /// Opens the basis file `path` for `mesh`, as `tvf filter MESH … --basis FILE` does: its
    /// discretization is rebuilt on the mesh from the id in the file (`entry`, `boundary`:
    /// refused if the file's differ), and the file is checked against the mesh's fingerprint
    /// and the complex's matrices, its size, payload checksum and values (read through once, in
    /// blocks: the pass `checking` reported to `progress`). Blocks of at most `block_bytes` (at
    /// least one stored column). Errors name the file.
    #[staticmethod]
    #[pyo3(signature = (path, mesh, block_bytes, entry = None, boundary = None, progress = None))]
    fn open(
        py: Python<'_>,
        path: PathBuf,
        mesh: &Mesh,
        block_bytes: usize,
        entry: Option<&str>,
        boundary: Option<&str>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Self> {
        let boundary = match boundary {
            None => None,
            Some(name) => Some(BoundaryCondition::from_name(name).ok_or_else(|| {
                tvf_error(format!(
                    "'{name}' is not a boundary condition: tangential or normal"
                ))
            })?),
        };
        let interruption = Arc::new(Interruption::default());
        let observer = block_observer(progress, interruption.clone());
        let opened = interruptible(py, &interruption, || {
            let complex = basis_file_complex(builtin_catalog(), &path, &mesh.mesh, entry, boundary)
                .map_err(|e| from_error(&e))?;
            let key = BasisFileKey::new(&mesh.mesh, complex.as_ref());
            let blocks = BasisFileBlocks::open_with_observer(&path, &key, complex, Some(observer))
                .map_err(|e| from_error(&e))?;
            Ok::<_, PyErr>((blocks.map(|b| b.with_observer(None)), key))
        })??;
        let (opened, key) = opened;
        let blocks = opened.ok_or_else(|| {
            tvf_error(format!(
                "{}: the basis file is in the fields layout (written by an earlier tvf): it is \
                 not read in blocks",
                path.display()
            ))
        })?;
        Ok(Self {
            blocks: Arc::new(blocks.with_block_bytes(block_bytes.max(1))),
            mesh: mesh.mesh.clone(),
            path,
            key,
        })
    }

    /// Number of basis fields `d`.
    #[getter]
    fn len(&self) -> usize {
        self.blocks.len()
    }

    /// `(n0, n1, n2)` of the basis's complex.
    #[getter]
    fn dimensions(&self) -> (usize, usize, usize) {
        let c = self.blocks.complex();
        (
            c.potential_dimension(),
            c.field_dimension(),
            c.co_potential_dimension(),
        )
    }

    /// The complex id of the basis.
    #[getter]
    fn discretization(&self) -> String {
        self.blocks.complex().id().to_string()
    }

    /// Whether fields convert to and from face vectors.
    #[getter]
    fn has_sampling(&self) -> bool {
        self.blocks.complex().sampling().is_some()
    }

    /// Face vectors (`F × 3`) as field coefficients (`n1`), with the largest dropped normal
    /// component.
    fn field_of_face_vectors<'py>(
        &self,
        py: Python<'py>,
        vectors: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(Bound<'py, PyAny>, f64)> {
        let (field, normal) = face_vectors_in(self.blocks.complex().as_ref(), &vectors)?;
        Ok((field.into_pyarray(py).into_any(), normal))
    }

    /// Field coefficients (`n1`) sampled at the face centroids (`F × 3`).
    fn face_vectors_of_field<'py>(
        &self,
        py: Python<'py>,
        field: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let values = self.field(&field)?;
        face_vectors_out(py, self.blocks.complex().as_ref(), &values)
    }

    /// `(c, relative_rest)`: the Fourier coefficients `Uᵀ M1 v` (`d`) of the field `v` (`n1`)
    /// and `|v − U c| / |v|` (`M1` norms), one pass over the file for each.
    #[pyo3(signature = (field, progress = None))]
    fn coefficients<'py>(
        &self,
        py: Python<'py>,
        field: PyReadonlyArray1<'py, f64>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<(Bound<'py, PyAny>, f64)> {
        let values = self.field(&field)?;
        let (interruption, basis) = self.observed(progress);
        let analysis = interruptible(py, &interruption, || FourierAnalysis::new(&basis, &values))?
            .map_err(|e| from_error(&e))?;
        Ok((
            analysis.coefficients.into_pyarray(py).into_any(),
            analysis.relative_rest_norm,
        ))
    }

    /// The spectral filter of `tvf filter` (responses as its `--integrable`/`--cointegrable`
    /// specs; `rest_gain` `None`: the command line's default, the filters' gain at the basis's
    /// highest frequency): `(field, filtered_coefficients, rest_gain)`.
    #[pyo3(signature = (
        field, integrable, cointegrable, harmonic_gain, rest_gain = None, progress = None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn filter<'py>(
        &self,
        py: Python<'py>,
        field: PyReadonlyArray1<'py, f64>,
        integrable: &str,
        cointegrable: &str,
        harmonic_gain: f64,
        rest_gain: Option<f64>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, f64)> {
        let values = self.field(&field)?;
        let response = |what: &str, spec: &str| -> PyResult<FrequencyResponse> {
            spec.parse::<FrequencyResponse>()
                .map_err(|e| with_context(&format!("--{what} {spec}"), &e))
        };
        let (integrable, cointegrable) = (
            response("integrable", integrable)?,
            response("cointegrable", cointegrable)?,
        );
        let rest_gain = rest_gain.unwrap_or_else(|| {
            SpectralFilter::continued_rest_gain(&integrable, &cointegrable, &*self.blocks)
        });
        let filter = SpectralFilter {
            integrable,
            cointegrable,
            harmonic_gain,
            rest_gain,
        };
        let (interruption, basis) = self.observed(progress);
        let filtered = interruptible(py, &interruption, || filter.apply(&basis, &values))?
            .map_err(|e| from_error(&e))?;
        if let Some(i) = filtered.field.iter().position(|x| !x.is_finite()) {
            return Err(tvf_error(format!(
                "the filtered field is not finite (coefficient {i}): the gains times the \
                 field's coefficients overflow f64 arithmetic"
            )));
        }
        Ok((
            filtered.field.into_pyarray(py).into_any(),
            filtered.filtered_coefficients.into_pyarray(py).into_any(),
            rest_gain,
        ))
    }

    /// The fields `U c` (`m × n1`) of the rows `c` of `sets` (`m × d`), summed in basis order,
    /// all in one pass over the file.
    #[pyo3(signature = (sets, progress = None))]
    fn synthesize<'py>(
        &self,
        py: Python<'py>,
        sets: PyReadonlyArray2<'py, f64>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let rows = checked_rows(
            &sets,
            self.blocks.len(),
            "coefficients",
            "(the basis's size)",
        )?;
        let sets: Vec<&[f64]> = rows.iter().map(Vec::as_slice).collect();
        let (interruption, basis) = self.observed(progress);
        let fields = interruptible(py, &interruption, || basis.reconstruct_many(&sets))?
            .map_err(|e| from_error(&e))?;
        if let Some(i) = fields.iter().position(|f| f.iter().any(|x| !x.is_finite())) {
            return Err(tvf_error(format!(
                "the synthesised field {i} is not finite: its coefficients overflow f64 \
                 arithmetic"
            )));
        }
        let n1 = self.blocks.field_dimension();
        let array = Array2::from_shape_vec((fields.len(), n1), fields.concat())
            .map_err(|e| tvf_error(e.to_string()))?;
        Ok(array.into_pyarray(py).into_any())
    }

    /// Basis fields `indices` sampled at the face centroids (`F × 3 × len(indices)`), formed
    /// from their stored columns in one pass over the file.
    #[pyo3(signature = (indices, progress = None))]
    fn face_fields<'py>(
        &self,
        py: Python<'py>,
        indices: Vec<usize>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let d = self.blocks.len();
        if let Some(&i) = indices.iter().find(|&&i| i >= d) {
            return Err(tvf_error(format!(
                "basis field {i}: the basis has {d} fields"
            )));
        }
        let sets: Vec<Vec<f64>> = indices
            .iter()
            .map(|&i| (0..d).map(|j| f64::from(u8::from(i == j))).collect())
            .collect();
        let sets: Vec<&[f64]> = sets.iter().map(Vec::as_slice).collect();
        let sampling = self
            .blocks
            .complex()
            .require_sampling()
            .map_err(|e| from_error(&e))?;
        let (interruption, basis) = self.observed(progress);
        let columns = interruptible(py, &interruption, || -> PyResult<Vec<Vec<[f64; 3]>>> {
            let fields = basis.reconstruct_many(&sets).map_err(|e| from_error(&e))?;
            fields
                .iter()
                .map(|f| sampling.to_face_vectors(f).map_err(|e| from_error(&e)))
                .collect()
        })??;
        Ok(face_fields_to_numpy(py, &columns, sampling.face_count()))
    }

    /// The spline (`soft` false) or the reduced soft design (`soft` true) of the constraints of
    /// `constraints_json` (`origin` names them in messages) in this basis, as `tvf spline
    /// --basis FILE` / `tvf design --reduced --basis FILE`: only the rows of `U` the
    /// constraints touch are read (the pass `rows`), and the field synthesised
    /// (`synthesising`). Dict `field` (`n1`), `residuals`.
    #[pyo3(signature = (constraints_json, origin, soft, progress = None))]
    fn reduced<'py>(
        &self,
        py: Python<'py>,
        constraints_json: &str,
        origin: &str,
        soft: bool,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let complex = self.blocks.complex().as_ref();
        let (set, compiled) = constraints_on(&self.mesh, complex, constraints_json, origin)?;
        let (interruption, observed) = self.observed(progress);
        let basis: Arc<dyn FieldBasis> = Arc::new(observed);
        let field = interruptible(py, &interruption, || {
            let reduced = ReducedBasis::from_field_basis(basis, &compiled)?;
            solve_reduced(complex, soft, &reduced, &set, &compiled)
        })?
        .map_err(|e| with_context(origin, &e))?;
        result(py, field, &compiled, set.omega, origin)
    }

    /// The basis id compressed files carry (16 hex digits): every field formed once from the
    /// file, a block at a time (the pass `fields`).
    #[pyo3(signature = (progress = None))]
    fn basis_id(&self, py: Python<'_>, progress: Option<Py<PyAny>>) -> PyResult<String> {
        let (interruption, basis) = self.observed(progress);
        let id = interruptible(py, &interruption, || field_basis_id(&basis))?
            .map_err(|e| from_error(&e))?;
        Ok(format!("{id:016x}"))
    }

    /// Fields (rows of `fields`, `n1` each) compressed into the bytes of a `.tvfc` file, as
    /// `tvf compress MESH FIELD --basis FILE` writes it (see [`BasisBlocks::with_identified`]).
    #[pyo3(signature = (fields, pairs, bits = None, progress = None))]
    fn compress<'py>(
        &self,
        py: Python<'py>,
        fields: PyReadonlyArray2<'py, f64>,
        pairs: usize,
        bits: Option<u32>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let fingerprint = self.mesh.fingerprint();
        self.with_identified(py, progress, |basis, id, interruption| {
            compress_rows(
                py,
                basis,
                (fingerprint, id),
                fields,
                pairs,
                bits,
                interruption,
            )
        })
    }

    /// The fields (`frames × n1`) of `.tvfc` bytes, checked against the mesh and the basis id,
    /// as `tvf decompress MESH FILE.tvfc --basis FILE` reads them.
    #[pyo3(signature = (data, progress = None))]
    fn decompress<'py>(
        &self,
        py: Python<'py>,
        data: &[u8],
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let fingerprint = self.mesh.fingerprint();
        self.with_identified(py, progress, |basis, id, interruption| {
            decompress_rows(py, basis, (fingerprint, id), data, interruption)
        })
    }

    /// The whole basis loaded into memory (as `tvf.basis` returns it: `coefficients` `n1 × d`
    /// and `face_vectors` `F × 3 × d`), the file read and checked again.
    fn load<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let complex = self.blocks.complex().as_ref();
        let basis = detached(py, || load_basis(&self.path, &self.key, complex))?
            .map_err(|e| from_error(&e))?;
        basis_dict(py, complex, &basis, 0.0)
    }
}

impl BasisBlocks {
    /// Runs `work` on the basis and the id compressed files carry, as `tvf compress` and `tvf
    /// decompress` pick them: the file read in blocks, or — where its fields would not get the
    /// loaded basis's id (a non-diagonal `M1` whose co-potentials do not fit one block:
    /// [`BasisFileBlocks::forms_fields_as_loaded`]) — loaded whole, so that bytes compressed
    /// here decode with the command line's basis and the other way round. Read in blocks, the
    /// passes are reported to `progress` and `work` is given the [`Interruption`] they poll;
    /// loaded whole, nothing is reported (`None`).
    fn with_identified<R>(
        &self,
        py: Python<'_>,
        progress: Option<Py<PyAny>>,
        work: impl FnOnce(&dyn FieldBasis, u64, Option<&Interruption>) -> PyResult<R>,
    ) -> PyResult<R> {
        if self.blocks.forms_fields_as_loaded() {
            let (interruption, basis) = self.observed(progress);
            let id = interruptible(py, &interruption, || field_basis_id(&basis))?
                .map_err(|e| from_error(&e))?;
            return work(&basis, id, Some(&interruption));
        }
        let complex = self.blocks.complex().as_ref();
        let basis = detached(py, || load_basis(&self.path, &self.key, complex))?
            .map_err(|e| from_error(&e))?;
        let id = detached(py, || field_basis_id(&basis))?.map_err(|e| from_error(&e))?;
        work(&basis, id, None)
    }

    /// The blocks for one call: each pass reported to the Python callable `progress` (if any)
    /// and Ctrl+C polled at every block, through the [`Interruption`] returned (run the call
    /// with [`interruptible`] and it).
    fn observed(&self, progress: Option<Py<PyAny>>) -> (Arc<Interruption>, ObservedBasisFile) {
        let interruption = Arc::new(Interruption::default());
        let observer = block_observer(progress, interruption.clone());
        let basis = ObservedBasisFile::new(self.blocks.clone(), Some(observer));
        (interruption, basis)
    }

    /// A field's coefficients, checked: length `n1`, finite.
    fn field(&self, field: &PyReadonlyArray1<'_, f64>) -> PyResult<Vec<f64>> {
        checked_field(self.blocks.complex().as_ref(), field)
    }
}
