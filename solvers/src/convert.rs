//! Conversions between `sprs` and `faer` sparse matrices.
//!
//! faer's sparse Cholesky works on compressed-sparse-column matrices with `usize` indices;
//! the rest of the project assembles matrices with `sprs`. These helpers do the conversion,
//! reject non-finite values and extract one triangle of a symmetric matrix.

use crate::error::SolverError;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};

/// Checks that `matrix` is square and returns its dimension.
pub fn square_dimension(matrix: &sprs::CsMat<f64>) -> Result<usize, SolverError> {
    let (rows, cols) = matrix.shape();
    if rows != cols {
        return Err(SolverError::NotSquare { rows, cols });
    }
    Ok(rows)
}

/// Upper triangle (row ≤ column, diagonal included) of a square `sprs` matrix, CSC or CSR,
/// as a faer CSC matrix with sorted row indices.
///
/// Entries of the strict lower triangle are ignored, so a symmetric matrix may be given in
/// full storage or upper-triangular storage (not lower-only). Explicitly stored zeros are kept,
/// so the result's pattern depends only on the input's pattern.
/// Errors: [`SolverError::NotSquare`], [`SolverError::NonFinite`].
pub fn upper_triangle_csc(
    matrix: &sprs::CsMat<f64>,
) -> Result<SparseColMat<usize, f64>, SolverError> {
    square_dimension(matrix)?;
    csc_of_entries(matrix, |row, col| row <= col)
}

/// Full copy of a `sprs` matrix (any shape, CSC or CSR) as a faer CSC matrix.
///
/// Errors: [`SolverError::NonFinite`].
pub fn to_faer_csc(matrix: &sprs::CsMat<f64>) -> Result<SparseColMat<usize, f64>, SolverError> {
    csc_of_entries(matrix, |_, _| true)
}

/// The entries `(row, col)` of `matrix` (any shape, CSC or CSR) for which `keep` holds, as a
/// faer CSC matrix of the same shape with sorted row indices (explicit zeros kept). Every
/// entry, kept or not, must be finite.
///
/// Errors: [`SolverError::NonFinite`].
fn csc_of_entries(
    matrix: &sprs::CsMat<f64>,
    keep: impl Fn(usize, usize) -> bool,
) -> Result<SparseColMat<usize, f64>, SolverError> {
    let (rows, cols) = matrix.shape();
    let mut count = vec![0usize; cols + 1];
    for (value, (row, col)) in matrix.iter() {
        if !value.is_finite() {
            return Err(SolverError::NonFinite {
                context: "sparse matrix",
                row,
                col,
                value: *value,
            });
        }
        if keep(row, col) {
            count[col + 1] += 1;
        }
    }
    for j in 0..cols {
        count[j + 1] += count[j];
    }
    let col_ptr = count.clone();
    let mut next = count;
    let mut row_idx = vec![0usize; col_ptr[cols]];
    let mut values = vec![0.0f64; col_ptr[cols]];
    // CSC iteration is column-major with sorted rows; CSR iteration is row-major, so within a
    // column rows also arrive in increasing order. Either way each column ends up sorted.
    for (value, (row, col)) in matrix.iter() {
        if keep(row, col) {
            let slot = next[col];
            row_idx[slot] = row;
            values[slot] = *value;
            next[col] += 1;
        }
    }
    let symbolic = SymbolicSparseColMat::new_checked(rows, cols, col_ptr, None, row_idx);
    Ok(SparseColMat::new(symbolic, values))
}

/// The upper triangle of `C(σ) = d1ᵀ N⁻¹ d1 − σW` for every σ (`n1 × n1`): the matrix a mixed
/// pencil `(d1 W⁻¹ d1ᵀ, N)` with the diagonal mass `mass` (`N`, `n2` positive values) factors at
/// a shift, for `d1` (`n2 × n1`) and `W` (`n1 × n1`, full or upper storage). Its pattern is that
/// of `W` with `d1ᵀ d1` (edges of a common face), which for the Whitney 1-form mass adds nothing.
///
/// Errors: [`SolverError::NotSquare`], [`SolverError::DimensionMismatch`] (`d1` does not have
/// `n1` columns or `mass` has not `n2` values), [`SolverError::NonFinite`].
pub fn edge_schur_pattern(
    w: &sprs::CsMat<f64>,
    d1: &sprs::CsMat<f64>,
    mass: &[f64],
) -> Result<ShiftedPattern, SolverError> {
    let n1 = square_dimension(w)?;
    for (context, expected, actual) in [
        ("columns of d1 (the rows of W)", n1, d1.cols()),
        ("values of the mass (the rows of d1)", d1.rows(), mass.len()),
    ] {
        if expected != actual {
            return Err(SolverError::DimensionMismatch {
                context,
                expected,
                actual,
            });
        }
    }
    let mut weighted = sprs::TriMat::with_capacity((d1.rows(), n1), d1.nnz());
    for (&value, (f, e)) in d1.iter() {
        weighted.add_triplet(f, e, value / mass[f]);
    }
    let weighted: sprs::CsMat<f64> = weighted.to_csr();
    let gram: sprs::CsMat<f64> = &d1.transpose_view().to_csr() * &weighted;
    ShiftedPattern::new(
        &upper_triangle_csc(&gram.to_csc())?,
        &upper_triangle_csc(w)?,
    )
}

/// `A − shift · diag(mass)` restricted to the upper triangle, as a faer CSC matrix.
///
/// Every diagonal position is present in the result (added as an explicit entry if `matrix`
/// lacks it), so the pattern does not depend on `shift`.
/// Errors: [`SolverError::NotSquare`], [`SolverError::NonFinite`], [`SolverError::DimensionMismatch`].
pub fn shifted_upper_triangle(
    matrix: &sprs::CsMat<f64>,
    mass_diagonal: &[f64],
    shift: f64,
) -> Result<SparseColMat<usize, f64>, SolverError> {
    let upper = upper_triangle_csc(matrix)?;
    let n = upper.nrows();
    if mass_diagonal.len() != n {
        return Err(SolverError::DimensionMismatch {
            context: "mass diagonal length",
            expected: n,
            actual: mass_diagonal.len(),
        });
    }
    let col_ptr = upper.symbolic().col_ptr();
    let row_idx = upper.symbolic().row_idx();
    let values = upper.val();
    let mut new_ptr = Vec::with_capacity(n + 1);
    let mut new_rows = Vec::with_capacity(values.len() + n);
    let mut new_vals = Vec::with_capacity(values.len() + n);
    new_ptr.push(0);
    for j in 0..n {
        let mut has_diagonal = false;
        for p in col_ptr[j]..col_ptr[j + 1] {
            let i = row_idx[p];
            new_rows.push(i);
            if i == j {
                has_diagonal = true;
                new_vals.push(values[p] - shift * mass_diagonal[j]);
            } else {
                new_vals.push(values[p]);
            }
        }
        if !has_diagonal {
            // rows are sorted and all ≤ j, so the diagonal goes last
            new_rows.push(j);
            new_vals.push(-shift * mass_diagonal[j]);
        }
        new_ptr.push(new_rows.len());
    }
    let symbolic = SymbolicSparseColMat::new_checked(n, n, new_ptr, None, new_rows);
    Ok(SparseColMat::new(symbolic, new_vals))
}

/// The upper triangle of `A − σB` for any shift σ, on the union of the patterns of `A` and `B`
/// and the diagonal (so the pattern, and the fill-reducing analysis of a factorization, does
/// not depend on σ; entries present in only one of them are explicit zeros in the other).
#[derive(Debug, Clone)]
pub struct ShiftedPattern {
    /// Column pointers of the union pattern (upper triangle, CSC).
    col_ptr: Vec<usize>,
    /// Row indices of the union pattern, sorted within each column.
    row_idx: Vec<usize>,
    /// `A` on the union pattern.
    base: Vec<f64>,
    /// `B` on the same pattern.
    shift_values: Vec<f64>,
}

impl ShiftedPattern {
    /// The union pattern of the upper triangles `a` and `b` (both `n × n`, CSC, sorted rows,
    /// row ≤ column) and the diagonal, with the values of both.
    ///
    /// Errors: [`SolverError::DimensionMismatch`] if the sizes differ.
    pub fn new(
        a: &SparseColMat<usize, f64>,
        b: &SparseColMat<usize, f64>,
    ) -> Result<Self, SolverError> {
        let n = a.ncols();
        if b.ncols() != n || a.nrows() != n || b.nrows() != n {
            return Err(SolverError::DimensionMismatch {
                context: "shifted pattern",
                expected: n,
                actual: b.ncols(),
            });
        }
        let column = |m: &SparseColMat<usize, f64>, j: usize| {
            let range = m.symbolic().col_ptr()[j]..m.symbolic().col_ptr()[j + 1];
            m.symbolic().row_idx()[range.clone()]
                .iter()
                .copied()
                .zip(m.val()[range].iter().copied())
                .collect::<Vec<_>>()
        };
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(a.val().len() + b.val().len() + n);
        let (mut base, mut shift_values) = (Vec::new(), Vec::new());
        col_ptr.push(0);
        for j in 0..n {
            let mut entries: Vec<(usize, f64, f64)> = column(a, j)
                .into_iter()
                .map(|(i, v)| (i, v, 0.0))
                .chain(column(b, j).into_iter().map(|(i, v)| (i, 0.0, v)))
                .chain(std::iter::once((j, 0.0, 0.0)))
                .collect();
            entries.sort_by_key(|e| e.0);
            for (i, va, vb) in entries {
                let repeated = row_idx.len() > col_ptr[j] && row_idx.last() == Some(&i);
                if let (true, Some(a), Some(b)) =
                    (repeated, base.last_mut(), shift_values.last_mut())
                {
                    *a += va;
                    *b += vb;
                } else {
                    row_idx.push(i);
                    base.push(va);
                    shift_values.push(vb);
                }
            }
            col_ptr.push(row_idx.len());
        }
        Ok(Self {
            col_ptr,
            row_idx,
            base,
            shift_values,
        })
    }

    /// `A − shift · B` on the union pattern (upper triangle, CSC).
    pub fn at(&self, shift: f64) -> SparseColMat<usize, f64> {
        self.with_values(
            self.base
                .iter()
                .zip(&self.shift_values)
                .map(|(a, b)| a - shift * b)
                .collect(),
        )
    }

    /// `A` and `B` on the union pattern (upper triangles, CSC).
    pub fn parts(&self) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
        (
            self.with_values(self.base.clone()),
            self.with_values(self.shift_values.clone()),
        )
    }

    fn with_values(&self, values: Vec<f64>) -> SparseColMat<usize, f64> {
        let n = self.col_ptr.len() - 1;
        let symbolic = SymbolicSparseColMat::new_checked(
            n,
            n,
            self.col_ptr.clone(),
            None,
            self.row_idx.clone(),
        );
        SparseColMat::new(symbolic, values)
    }
}

/// `A − shift · M` restricted to the upper triangle for a sparse symmetric `mass` (full or
/// upper storage; its strict lower triangle is ignored), on the union of both patterns and
/// the diagonal (see [`ShiftedPattern`]): the generalisation of [`shifted_upper_triangle`] to
/// consistent masses.
///
/// Errors: [`SolverError::NotSquare`], [`SolverError::NonFinite`],
/// [`SolverError::DimensionMismatch`].
pub fn shifted_upper_triangle_with_mass(
    matrix: &sprs::CsMat<f64>,
    mass: &sprs::CsMat<f64>,
    shift: f64,
) -> Result<SparseColMat<usize, f64>, SolverError> {
    let pattern = ShiftedPattern::new(&upper_triangle_csc(matrix)?, &upper_triangle_csc(mass)?)?;
    Ok(pattern.at(shift))
}
