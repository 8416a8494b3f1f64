//! Masses from Python: a diagonal (a 1-D array) or a sparse symmetric positive definite matrix
//! (CSR parts) becomes a [`Mass`] of the seam, named in every error by the argument it came
//! from; and how a complex stores its masses, for `Complex.masses` and `tvf.operators`.

use crate::arrays::{csr_from_parts, CsrParts};
use crate::errors::tvf_error;
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tvf_core::discretization::{HodgeComplex, Mass, MassForm};

/// A mass as Python passes it (`tvf/_arrays.py` decides which): the `n` entries of a diagonal,
/// or the CSR parts of an `n × n` sparse matrix with off-diagonal entries.
#[derive(FromPyObject)]
pub enum MassInput<'py> {
    /// The diagonal.
    Diagonal(PyReadonlyArray1<'py, f64>),
    /// `(indptr, indices, data, shape)`.
    Sparse(CsrParts<'py>),
}

/// Which matrix an argument holds: the mass `M`, or its inverse `M⁻¹` (the `M2_inverse=` of
/// `Complex.from_matrices`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Given {
    /// The argument is `M`.
    Mass,
    /// The argument is `M⁻¹`.
    Inverse,
}

/// The [`Mass`] an argument gives, named `what` in errors (`M0`, `M1`, `M2`, `M2_inverse (M2⁻¹)`,
/// `M`). A diagonal may be zero only where no face uses the node; a sparse matrix must be square,
/// finite and symmetric to round-off here, and is checked positive definite on the used nodes
/// (its Cholesky factorization) when the complex is built. A diagonal inverse becomes the
/// diagonal of its reciprocals, so that the operators stay sparse matrices.
pub fn mass_from_input(what: &'static str, input: MassInput<'_>, given: Given) -> PyResult<Mass> {
    let checked = match (input, given) {
        (MassInput::Diagonal(values), Given::Mass) => {
            Mass::diagonal(what, values.as_array().to_vec())
        }
        (MassInput::Diagonal(values), Given::Inverse) => {
            Mass::diagonal(what, values.as_array().to_vec()).map(|inverse| inverse.inverse())
        }
        (MassInput::Sparse(parts), Given::Mass) => Mass::sparse(what, csr_from_parts(what, parts)?),
        (MassInput::Sparse(parts), Given::Inverse) => {
            Mass::sparse_inverse(what, csr_from_parts(what, parts)?)
        }
    };
    checked.map_err(|e| tvf_error(e.to_string()))
}

/// `M2` given directly, checked to be diagonal: the co-exact eigenproblem's mass is the
/// co-potential mass `M2⁻¹`, which tvf's eigensolvers need sparse, and the inverse of an `M2`
/// with off-diagonal entries is dense.
pub fn direct_co_potential_mass(m2: Mass) -> PyResult<Mass> {
    if m2.is_diagonal() {
        Ok(m2)
    } else {
        Err(tvf_error(
            "M2 has off-diagonal entries, so its inverse, the co-potential mass, is dense; tvf \
             needs the co-potential mass sparse: give M2 as a diagonal, or the sparse \
             co-potential mass as M2_inverse",
        ))
    }
}

/// `{"M0": {...}, "M1": {...}, "M2": {...}}`: for each mass its `storage` (`diagonal` or
/// `sparse`), its `form` (`direct`: the sparse matrix is `M`; `inverse`: it is `M⁻¹`, and `M`
/// is dense) and `key`, the key of `tvf.operators` that holds the sparse matrix (`M2` or
/// `M2_inverse`).
pub fn mass_description<'py>(
    py: Python<'py>,
    complex: &dyn HodgeComplex,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    for (name, mass) in named_masses(complex) {
        let entry = PyDict::new(py);
        entry.set_item(
            "storage",
            if mass.is_diagonal() {
                "diagonal"
            } else {
                "sparse"
            },
        )?;
        entry.set_item("form", mass.form().name())?;
        entry.set_item("key", stored_key(name, mass.form()))?;
        out.set_item(name, entry)?;
    }
    Ok(out)
}

/// The three masses with their names.
pub fn named_masses(complex: &dyn HodgeComplex) -> [(&'static str, &Mass); 3] {
    [
        ("M0", complex.m0()),
        ("M1", complex.m1()),
        ("M2", complex.m2()),
    ]
}

/// The key of the stored (sparse) matrix of mass `name`: `name`, or `name_inverse` when the
/// stored matrix is the inverse (as `tvf operators` names its files).
pub fn stored_key(name: &str, form: MassForm) -> String {
    match form {
        MassForm::Direct => name.to_string(),
        MassForm::Inverse => format!("{name}_inverse"),
    }
}
