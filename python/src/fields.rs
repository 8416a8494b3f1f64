//! Field functions: the Hodge decomposition, Fourier coefficients, spectral filters and
//! compression, on field coefficient vectors (`n1` entries; Python converts face vectors).

use crate::arrays::checked_rows;
use crate::basis_parts::BasisParts;
use crate::complex::Complex;
use crate::errors::{from_error, tvf_error, with_context};
use crate::interrupt::{detached, interruptible, Interruption};
use numpy::{IntoPyArray, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_discretizations::HodgeDecomposer;
use tvf_spectral::{
    basis_id, CoefficientCoding, CompressedFields, FieldBasis, FieldCodec, FrequencyResponse,
    SpectralFilter,
};

/// Face vectors (`F × 3`) as field coefficients, with the largest dropped normal component.
#[pyfunction]
pub fn from_face_vectors<'py>(
    py: Python<'py>,
    complex: &Complex,
    vectors: PyReadonlyArray2<'py, f64>,
) -> PyResult<(Bound<'py, PyAny>, f64)> {
    let (field, normal) = face_vectors_in(complex.complex.as_ref(), &vectors)?;
    Ok((field.into_pyarray(py).into_any(), normal))
}

/// Field coefficients sampled at the face centroids (`F × 3`).
#[pyfunction]
pub fn to_face_vectors<'py>(
    py: Python<'py>,
    complex: &Complex,
    field: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let values = complex.field(&field)?;
    face_vectors_out(py, complex.complex.as_ref(), &values)
}

/// Face vectors (`F × 3`, finite) of `complex`'s faces as its field coefficients (`n1`),
/// projected onto the face planes, with the largest normal component dropped.
pub fn face_vectors_in(
    complex: &dyn HodgeComplex,
    vectors: &PyReadonlyArray2<'_, f64>,
) -> PyResult<(Vec<f64>, f64)> {
    let sampling = complex.require_sampling().map_err(|e| from_error(&e))?;
    let vectors = crate::arrays::numpy_to_vectors(vectors)?;
    if let Some(t) = vectors
        .iter()
        .position(|v| v.iter().any(|x| !x.is_finite()))
    {
        return Err(tvf_error(format!("field: non-finite vector at face {t}")));
    }
    let projection = sampling
        .from_face_vectors(&vectors)
        .map_err(|e| from_error(&e))?;
    let normal = projection.max_normal_part();
    Ok((projection.field, normal))
}

/// Field coefficients `field` (`n1`) of `complex` sampled at the face centroids (`F × 3`).
pub fn face_vectors_out<'py>(
    py: Python<'py>,
    complex: &dyn HodgeComplex,
    field: &[f64],
) -> PyResult<Bound<'py, PyAny>> {
    let sampling = complex.require_sampling().map_err(|e| from_error(&e))?;
    let vectors = sampling
        .to_face_vectors(field)
        .map_err(|e| from_error(&e))?;
    Ok(crate::arrays::vectors_to_numpy(py, &vectors))
}

/// The Hodge decomposition: dict of `integrable`, `cointegrable`, `harmonic` (`n1` each),
/// `potential` (`n0`), `co_potential` (`n2`).
#[pyfunction]
pub fn decompose<'py>(
    py: Python<'py>,
    complex: &Complex,
    field: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let c = complex.complex.as_ref();
    let values = complex.field(&field)?;
    let parts = detached(py, || {
        HodgeDecomposer::new(c).and_then(|d| d.decompose(&values))
    })?
    .map_err(|e| {
        with_context(
            &format!("{}: cannot decompose the field", complex.label),
            &e,
        )
    })?;
    let out = PyDict::new(py);
    out.set_item("integrable", parts.integrable.into_pyarray(py))?;
    out.set_item("cointegrable", parts.cointegrable.into_pyarray(py))?;
    out.set_item("harmonic", parts.harmonic.into_pyarray(py))?;
    out.set_item("potential", parts.potential.into_pyarray(py))?;
    out.set_item("co_potential", parts.co_potential.into_pyarray(py))?;
    Ok(out)
}

/// Fourier coefficients `Uᵀ M1 v` of a field in a basis, and the relative norm of the rest.
#[pyfunction]
pub fn coefficients<'py>(
    py: Python<'py>,
    complex: &Complex,
    basis: BasisParts<'py>,
    field: PyReadonlyArray1<'py, f64>,
) -> PyResult<(Bound<'py, PyAny>, f64)> {
    let basis = complex.basis(basis)?;
    let values = complex.field(&field)?;
    let analysis = py
        .detach(|| tvf_spectral::FourierAnalysis::new(&basis, &values))
        .map_err(|e| from_error(&e))?;
    Ok((
        analysis.coefficients.into_pyarray(py).into_any(),
        analysis.relative_rest_norm,
    ))
}

/// A spectral filter (responses as the command line's `--integrable`/`--cointegrable` specs):
/// returns the filtered field and the filtered coefficients.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn filter<'py>(
    py: Python<'py>,
    complex: &Complex,
    basis: BasisParts<'py>,
    field: PyReadonlyArray1<'py, f64>,
    integrable: &str,
    cointegrable: &str,
    harmonic_gain: f64,
    rest_gain: f64,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let basis = complex.basis(basis)?;
    let values = complex.field(&field)?;
    let response = |what: &str, spec: &str| -> PyResult<FrequencyResponse> {
        spec.parse::<FrequencyResponse>()
            .map_err(|e| with_context(&format!("--{what} {spec}"), &e))
    };
    let filter = SpectralFilter {
        integrable: response("integrable", integrable)?,
        cointegrable: response("cointegrable", cointegrable)?,
        harmonic_gain,
        rest_gain,
    };
    let filtered = py
        .detach(|| filter.apply(&basis, &values))
        .map_err(|e| from_error(&e))?;
    Ok((
        filtered.field.into_pyarray(py).into_any(),
        filtered.filtered_coefficients.into_pyarray(py).into_any(),
    ))
}

/// Fields (rows of `fields`, `n1` each) compressed into the bytes of a `.tvfc` file.
#[pyfunction]
#[pyo3(signature = (complex, basis, fields, pairs, bits = None))]
pub fn compress<'py>(
    py: Python<'py>,
    complex: &Complex,
    basis: BasisParts<'py>,
    fields: PyReadonlyArray2<'py, f64>,
    pairs: usize,
    bits: Option<u32>,
) -> PyResult<Bound<'py, PyBytes>> {
    let basis = complex.basis(basis)?;
    let stamp = (complex.mesh.fingerprint(), basis_id(&basis));
    compress_rows(py, &basis, stamp, fields, pairs, bits, None)
}

/// The fields of `.tvfc` bytes (one row each), checked against the mesh and the basis.
#[pyfunction]
pub fn decompress<'py>(
    py: Python<'py>,
    complex: &Complex,
    basis: BasisParts<'py>,
    data: &[u8],
) -> PyResult<Bound<'py, PyAny>> {
    let basis = complex.basis(basis)?;
    let stamp = (complex.mesh.fingerprint(), basis_id(&basis));
    decompress_rows(py, &basis, stamp, data, None)
}

/// Fields (rows of `fields`, `n1` each, finite) compressed in `basis` into the bytes of a
/// `.tvfc` file keeping `pairs` pairs (`bits`: quantised, else 64-bit coefficients), stamped
/// with `(mesh fingerprint, basis id)`. With the `interruption` of a basis whose passes poll it
/// (a basis file read in blocks), the fields are encoded in turn on the calling thread (each a
/// pass over the file, where Ctrl+C is noticed); without, in parallel.
pub fn compress_rows<'py>(
    py: Python<'py>,
    basis: &dyn FieldBasis,
    (mesh_fingerprint, id): (u64, u64),
    fields: PyReadonlyArray2<'py, f64>,
    pairs: usize,
    bits: Option<u32>,
    interruption: Option<&Interruption>,
) -> PyResult<Bound<'py, PyBytes>> {
    let coding = match bits {
        Some(bits) => CoefficientCoding::Quantized { bits },
        None => CoefficientCoding::Float64,
    };
    let codec =
        FieldCodec::new(basis, mesh_fingerprint, id, pairs, coding).map_err(|e| from_error(&e))?;
    let rows = checked_rows(
        &fields,
        basis.field_dimension(),
        "fields",
        "the field dimension",
    )?;
    let file = match interruption {
        Some(interruption) if !rows.is_empty() => interruptible(py, interruption, || {
            let frames: Result<Vec<_>, _> = rows.iter().map(|row| codec.encode(row)).collect();
            frames.map(|frames| CompressedFields {
                header: *codec.header(),
                frames,
            })
        })?,
        _ => detached(py, || codec.compress(&rows))?,
    }
    .map_err(|e| from_error(&e))?;
    Ok(PyBytes::new(py, &file.to_bytes()))
}

/// The fields (`frames × n1`) of `.tvfc` bytes decoded in `basis`, the file checked against
/// `(mesh fingerprint, basis id)`; `interruption`: the one `basis`'s passes poll, if they do.
pub fn decompress_rows<'py>(
    py: Python<'py>,
    basis: &dyn FieldBasis,
    (mesh_fingerprint, id): (u64, u64),
    data: &[u8],
    interruption: Option<&Interruption>,
) -> PyResult<Bound<'py, PyAny>> {
    let file = CompressedFields::from_bytes(data).map_err(|e| from_error(&e))?;
    let codec = FieldCodec::for_file(basis, mesh_fingerprint, id, &file.header)
        .map_err(|e| from_error(&e))?;
    let decompress = || codec.decompress(&file);
    let fields = match interruption {
        Some(interruption) => interruptible(py, interruption, decompress)?,
        None => detached(py, decompress)?,
    }
    .map_err(|e| from_error(&e))?;
    let flat: Vec<f64> = fields.concat();
    let array =
        numpy::ndarray::Array2::from_shape_vec((fields.len(), basis.field_dimension()), flat)
            .map_err(|e| tvf_error(e.to_string()))?;
    Ok(array.into_pyarray(py).into_any())
}
