//! `tvf._native`: the Rust half of the `tvf` Python package. Every function takes and returns
//! numpy arrays and plain Python values; the Python half (`python/tvf/`) turns sparse matrices
//! into `scipy.sparse.csr_matrix`, checks dtypes and shapes, and carries the documentation.
//! Long computations release the GIL and stop on Ctrl+C (`interrupt`); errors are `tvf.TvfError` with the message the `tvf`
//! command line prints for the same problem.
#![forbid(unsafe_code)]

use pyo3::prelude::*;

mod arrays;
mod basis;
mod basis_file;
mod basis_parts;
mod block_observer;
mod check;
mod compare;
mod complex;
mod convergence;
mod design;
mod eigsh;
mod errors;
mod fields;
mod interrupt;
mod linear_operator;
mod masses;
mod mesh;
mod operators;
mod progress;

/// The module `tvf._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("TvfError", m.py().get_type::<errors::TvfError>())?;
    m.add_class::<mesh::Mesh>()?;
    m.add_class::<complex::Complex>()?;
    m.add_class::<linear_operator::Operator>()?;
    m.add_class::<basis_file::BasisBlocks>()?;
    m.add_function(wrap_pyfunction!(mesh::read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(complex::discretizations, m)?)?;
    m.add_function(wrap_pyfunction!(operators::operators, m)?)?;
    m.add_function(wrap_pyfunction!(basis::basis, m)?)?;
    m.add_function(wrap_pyfunction!(basis_file::basis_file_summary, m)?)?;
    m.add_function(wrap_pyfunction!(fields::from_face_vectors, m)?)?;
    m.add_function(wrap_pyfunction!(fields::to_face_vectors, m)?)?;
    m.add_function(wrap_pyfunction!(fields::decompose, m)?)?;
    m.add_function(wrap_pyfunction!(fields::coefficients, m)?)?;
    m.add_function(wrap_pyfunction!(fields::filter, m)?)?;
    m.add_function(wrap_pyfunction!(fields::compress, m)?)?;
    m.add_function(wrap_pyfunction!(fields::decompress, m)?)?;
    m.add_function(wrap_pyfunction!(design::reduced, m)?)?;
    m.add_function(wrap_pyfunction!(design::design, m)?)?;
    m.add_function(wrap_pyfunction!(eigsh::eigsh, m)?)?;
    m.add_function(wrap_pyfunction!(check::check, m)?)?;
    m.add_function(wrap_pyfunction!(convergence::convergence, m)?)?;
    m.add_function(wrap_pyfunction!(check::check_builder, m)?)?;
    m.add_function(wrap_pyfunction!(compare::compare, m)?)?;
    Ok(())
}
