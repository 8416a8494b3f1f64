//! `tvf.operators`: every matrix of a complex — sparse ones as CSR parts, dense ones as
//! [`Operator`]s applied through the Rust operator — and the face frames.

use crate::arrays::csr_to_parts;
use crate::complex::Complex;
use crate::linear_operator::Operator;
use crate::masses::{named_masses, stored_key};
use numpy::ndarray::{Array2, Array3};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tvf_core::discretization::{Factor, HodgeOperators, LinearOperator, MassForm};

/// `{name: value}` where `value` is the CSR parts `(indptr, indices, data, shape)` of a sparse
/// matrix or an [`Operator`]:
///
/// - masses: `M0`, `M1`, `M2` as their stored sparse matrices (a diagonal or a sparse SPD
///   matrix); a mass stored as its inverse is `{name}_inverse` (CSR) and `{name}` (an
///   [`Operator`], `M x` by a Cholesky solve with the stored inverse);
/// - `d0`, `d1`, `S0` (always sparse), `J` where the complex has a rotation (sparse);
/// - `S2`, `S`, `L`, `B`, `div`, `curl` (and `div_other`, `curl_other` with a rotation): CSR
///   where every mass involved is diagonal, else an [`Operator`];
/// - `frames` (`F × 2 × 3`) where the complex has a sampling;
/// - on an intrinsic triangulation: `intrinsic_faces` (`F_i × 3`, counter-clockwise vertex
///   triples), `intrinsic_edges` (`E_i × 2`, the reference direction of each edge: `d0`'s
///   `−1`, `+1`), `intrinsic_edge_lengths` (`E_i`) and `intrinsic_vertex_positions` (`V_i × 3`,
///   where each intrinsic vertex sits on the input surface).
#[pyfunction]
pub fn operators<'py>(py: Python<'py>, complex: &Complex) -> PyResult<Bound<'py, PyDict>> {
    let c = complex.complex.as_ref();
    // Derived operators are computed (and cached) without the GIL.
    py.detach(|| {
        c.potential_stiffness();
        c.co_potential_stiffness();
        c.dirichlet_energy();
        c.hodge_laplacian();
        c.biharmonic_energy();
        c.potential_divergence();
        c.co_potential_curl();
        c.other_divergence();
        c.other_curl();
    });
    let out = PyDict::new(py);
    let put_sparse = |name: &str, m: &sprs::CsMat<f64>| out.set_item(name, csr_to_parts(py, m)?);
    let put = |name: &str, operator: &LinearOperator| match operator.as_sparse() {
        Some(matrix) => put_sparse(name, matrix),
        None => out.set_item(name, Operator::new(name, operator.clone())),
    };
    put_sparse("d0", c.d0())?;
    put_sparse("d1", c.d1())?;
    for (name, mass) in named_masses(c) {
        put_sparse(&stored_key(name, mass.form()), &mass.stored_matrix())?;
        if mass.form() == MassForm::Inverse {
            let dense = LinearOperator::product(1.0, vec![Factor::Mass(mass.clone())]);
            out.set_item(name, Operator::new(name, dense))?;
        }
    }
    put_sparse("S0", c.potential_stiffness())?;
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
        put_sparse("J", rotation.rotation())?;
    }
    if let Some(sampling) = c.sampling() {
        let faces = sampling.face_count();
        let frames = Array3::from_shape_fn((faces, 2, 3), |(t, a, k)| sampling.frame(t)[a][k]);
        out.set_item("frames", frames.into_pyarray(py))?;
    }
    if let Some(tri) = c.intrinsic_triangulation() {
        let faces = Array2::from_shape_fn((tri.face_count(), 3), |(t, c)| tri.faces()[t][c]);
        let edges = Array2::from_shape_fn((tri.edge_count(), 2), |(e, k)| tri.edge_vertices(e)[k]);
        let positions = &c.potential_nodes().positions;
        let vertices = Array2::from_shape_fn((positions.len(), 3), |(v, k)| positions[v][k]);
        out.set_item("intrinsic_faces", faces.into_pyarray(py))?;
        out.set_item("intrinsic_edges", edges.into_pyarray(py))?;
        out.set_item(
            "intrinsic_edge_lengths",
            tri.lengths().to_vec().into_pyarray(py),
        )?;
        out.set_item("intrinsic_vertex_positions", vertices.into_pyarray(py))?;
    }
    Ok(out)
}
