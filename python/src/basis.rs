//! `tvf.basis`: the Fourier basis of a complex (the way back from Python's arrays is
//! `basis_parts.rs`).

use crate::arrays::{face_fields_to_numpy, mat_to_numpy};
use crate::complex::Complex;
use crate::errors::{from_error, tvf_error, with_context};
use crate::interrupt::{interruptible, Interruption};
use crate::progress::Progress;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_spectral::{compute_basis, BasisRequest, SpectralBasis};

/// The `k` lowest eigenfields of `L` (the complete basis if `k ≥ n1`), as a dict:
/// `eigenvalues` (`k`), `families` (list of `harmonic`/`integrable`/`cointegrable`),
/// `coefficients` (`n1 × k`, `Uᵀ M1 U = I`), `face_vectors` (`F × 3 × k`, sampled at the face
/// centroids; `None` without sampling), `discretization`, `seconds`.
#[pyfunction]
#[pyo3(signature = (complex, k, seed = 0, progress = None))]
pub fn basis<'py>(
    py: Python<'py>,
    complex: &Complex,
    k: usize,
    seed: u64,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    if k == 0 {
        return Err(tvf_error("-k 0: ask for at least one eigenfield"));
    }
    let c = complex.complex.as_ref();
    let interruption = Interruption::default();
    let reporter = Progress::new(progress, &interruption);
    let computed = interruptible(py, &interruption, || {
        let callback =
            |p: &tvf_spectral::BasisProgress| reporter.report(p.stage.name(), p.done, p.wanted);
        let request = if k >= c.field_dimension() {
            BasisRequest::complete()
        } else {
            BasisRequest::fields(k)
        };
        compute_basis(c, &request.with_seed(seed).with_progress(&callback))
    })?;
    let basis = computed
        .map_err(|e| with_context(&format!("{}: cannot compute the basis", complex.label), &e))?;
    let seconds = basis.report().map_or(0.0, |r| r.seconds);
    basis_dict(py, c, &basis, seconds)
}

/// The dict `tvf.basis` returns for `basis`, a basis of `c` (see [`basis`]; `seconds` the time
/// it took).
pub fn basis_dict<'py>(
    py: Python<'py>,
    c: &dyn HodgeComplex,
    basis: &SpectralBasis,
    seconds: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("eigenvalues", basis.eigenvalues().to_vec().into_pyarray(py))?;
    let families: Vec<&str> = basis.families().iter().map(|f| f.name()).collect();
    out.set_item("families", families)?;
    out.set_item("coefficients", mat_to_numpy(py, &basis.fields()))?;
    let face_vectors = match c.sampling() {
        Some(sampling) => {
            let fields = basis.fields();
            let columns = py.detach(|| {
                (0..basis.len())
                    .map(|j| {
                        let column: Vec<f64> = fields.col(j).iter().copied().collect();
                        sampling.to_face_vectors(&column)
                    })
                    .collect::<Result<Vec<_>, _>>()
            });
            let columns = columns.map_err(|e| from_error(&e))?;
            Some(face_fields_to_numpy(py, &columns, sampling.face_count()))
        }
        None => None,
    };
    out.set_item("face_vectors", face_vectors)?;
    out.set_item("discretization", c.id())?;
    out.set_item("seconds", seconds)?;
    Ok(out)
}
