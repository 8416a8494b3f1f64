//! `tvf.operators`: every matrix of a complex as CSR parts, and the face frames.

use crate::arrays::csr_to_parts;
use crate::complex::Complex;
use numpy::ndarray::Array3;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tvf_core::discretization::sparse::diagonal;
use tvf_core::discretization::HodgeOperators;

/// `{name: (indptr, indices, data, shape)}` for d0, d1, M0, M1, M2, S0, S2, S, L, B, div, curl,
/// (div_other, curl_other, J where the complex has a rotation), and `frames` (`F × 2 × 3`) where
/// it has a sampling.
#[pyfunction]
pub fn operators<'py>(py: Python<'py>, complex: &Complex) -> PyResult<Bound<'py, PyDict>> {
    let c = complex.complex.as_ref();
    // Derived operators are computed (and cached) without the GIL.
    py.detach(|| {
        c.dirichlet_energy();
        c.hodge_laplacian();
        c.biharmonic_energy();
        c.other_divergence();
        c.other_curl();
    });
    let out = PyDict::new(py);
    let put = |name: &str, m: &sprs::CsMat<f64>| out.set_item(name, csr_to_parts(py, m)?);
    put("d0", c.d0())?;
    put("d1", c.d1())?;
    put("M0", &diagonal(c.m0().values()))?;
    put("M1", &diagonal(c.m1().values()))?;
    put("M2", &diagonal(c.m2().values()))?;
    put("S0", c.potential_stiffness())?;
    put("S2", c.co_potential_stiffness())?;
    put("S", c.dirichlet_energy())?;
    put("L", c.hodge_laplacian())?;
    put("B", c.biharmonic_energy())?;
    put("div", c.potential_divergence())?;
    put("curl", c.co_potential_curl())?;
    if let (Some(div), Some(curl)) = (c.other_divergence(), c.other_curl()) {
        put("div_other", div)?;
        put("curl_other", curl)?;
    }
    if let Some(rotation) = c.rotation() {
        put("J", rotation.rotation())?;
    }
    if let Some(sampling) = c.sampling() {
        let faces = sampling.face_count();
        let frames = Array3::from_shape_fn((faces, 2, 3), |(t, a, k)| sampling.frame(t)[a][k]);
        out.set_item("frames", frames.into_pyarray(py))?;
    }
    Ok(out)
}
