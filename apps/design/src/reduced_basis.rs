//! [`ReducedBasis`]: the eigenfields `U` stored row by row, with the eigenvalues, for the reduced
//! solvers; and [`RowMajorFields`], the row-major `U` in `f64` or `f32` with the one
//! multithreaded map `x = U v` both precisions share.

use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use rayon::prelude::*;
use tvf_spectral::{FieldFamily, SpectralBasis};

/// Rows per parallel task in the maps `x = U v`.
const ROWS_PER_TASK: usize = 2048;

/// `d` basis fields `U` (`n1 × d`, `Uᵀ M1 U = I`) stored **row-major** (row `r` = the `d`
/// values of coefficient `r` across the basis), with eigenvalues `λ_i` of the Hodge–Laplacian
/// (units 1/length²) and a harmonic flag per field.
///
/// Row-major storage makes both reduced-solver hot paths contiguous: a constraint row
/// `C = C̃ U` reads only the few rows of `U` its face touches, and `x = U v` is one dot product
/// per output coefficient, streaming `U` exactly once.
#[derive(Debug, Clone)]
pub struct ReducedBasis {
    fields: RowMajorFields<f64>,
    eigenvalues: Vec<f64>,
    harmonic: Vec<bool>,
}

/// `U` (`n × d`) stored row-major in precision `T` (`f64`, or `f32` for the fast map with half
/// the memory traffic), with the map `x = U v`.
#[derive(Debug, Clone)]
pub struct RowMajorFields<T> {
    rows: Vec<T>,
    len: usize,
    field_dimension: usize,
}

/// `U` in single precision, for the fast map `x = U v`.
pub type ReducedBasisF32 = RowMajorFields<f32>;

/// The number types of [`RowMajorFields`]: `f64` and `f32`.
pub trait FieldScalar:
    Copy + Send + Sync + Default + std::ops::Add<Output = Self> + std::ops::Mul<Output = Self>
{
    /// Independent accumulators of a dot product or sum (lets the compiler vectorise: 4 for
    /// `f64`, 8 for `f32`, one 256-bit register each).
    const LANES: usize;
}

impl FieldScalar for f64 {
    const LANES: usize = 4;
}

impl FieldScalar for f32 {
    const LANES: usize = 8;
}

impl ReducedBasis {
    /// Copies a spectral basis into row-major storage. Fields of the harmonic family, and fields
    /// with eigenvalue below `1e-10 · λ_max`, are flagged harmonic.
    pub fn from_spectral(basis: &SpectralBasis) -> Result<Self, DesignError> {
        let u = basis.fields();
        let (n, d) = (u.nrows(), u.ncols());
        let mut rows = vec![0.0; n * d];
        rows.par_chunks_mut(d.max(1) * 256)
            .enumerate()
            .for_each(|(block, out)| {
                let first = block * 256;
                for (k, row) in out.chunks_mut(d.max(1)).enumerate() {
                    for (j, value) in row.iter_mut().enumerate() {
                        *value = u[(first + k, j)];
                    }
                }
            });
        let harmonic = basis
            .families()
            .iter()
            .map(|f| *f == FieldFamily::Harmonic)
            .collect();
        Self::from_row_major(rows, n, basis.eigenvalues().to_vec(), harmonic)
    }

    /// A basis from row-major values (`field_dimension × d`), eigenvalues and harmonic flags
    /// (`d` each). Eigenvalues must be finite and non-negative; small ones are flagged harmonic as
    /// in [`ReducedBasis::from_spectral`].
    pub fn from_row_major(
        rows: Vec<f64>,
        field_dimension: usize,
        eigenvalues: Vec<f64>,
        mut harmonic: Vec<bool>,
    ) -> Result<Self, DesignError> {
        let d = eigenvalues.len();
        if harmonic.len() != d {
            return Err(DesignError::DimensionMismatch {
                what: "harmonic flags",
                expected: d,
                actual: harmonic.len(),
            });
        }
        if rows.len() != field_dimension * d {
            return Err(DesignError::DimensionMismatch {
                what: "basis values (n1 × d)",
                expected: field_dimension * d,
                actual: rows.len(),
            });
        }
        if let Some(&bad) = eigenvalues.iter().find(|l| !(l.is_finite() && **l >= 0.0)) {
            return Err(DesignError::BadParameter {
                what: "basis eigenvalue",
                value: bad,
            });
        }
        let max = eigenvalues.iter().fold(0.0f64, |m, &l| m.max(l));
        for (flag, &l) in harmonic.iter_mut().zip(&eigenvalues) {
            *flag |= l <= 1e-10 * max;
        }
        Ok(Self {
            fields: RowMajorFields {
                rows,
                len: d,
                field_dimension,
            },
            eigenvalues,
            harmonic,
        })
    }

    /// Number of basis fields `d`.
    pub fn len(&self) -> usize {
        self.eigenvalues.len()
    }

    /// Whether the basis has no field.
    pub fn is_empty(&self) -> bool {
        self.eigenvalues.is_empty()
    }

    /// Dimension `n1` of the field space.
    pub fn field_dimension(&self) -> usize {
        self.fields.field_dimension
    }

    /// Eigenvalues `λ_i` (`d` entries, 1/length²).
    pub fn eigenvalues(&self) -> &[f64] {
        &self.eigenvalues
    }

    /// Harmonic flag of every field (`d` entries).
    pub fn harmonic(&self) -> &[bool] {
        &self.harmonic
    }

    /// Row `r` of `U` (`d` values): coefficient `r` of every basis field.
    pub fn row(&self, r: usize) -> &[f64] {
        let d = self.len();
        &self.fields.rows[r * d..(r + 1) * d]
    }

    /// The eigenvalues with harmonic ones (0) replaced by a tenth of the lowest non-harmonic
    /// eigenvalue (Section 7), so that `D = Λ² + ωΛ` is invertible.
    pub fn regularised_eigenvalues(&self) -> Result<Vec<f64>, DesignError> {
        let lowest = self
            .eigenvalues
            .iter()
            .zip(&self.harmonic)
            .filter(|(_, h)| !**h)
            .map(|(l, _)| *l)
            .fold(f64::INFINITY, f64::min);
        if !lowest.is_finite() {
            return Err(DesignError::BadBasis(
                "no non-harmonic field to scale the harmonic ones".into(),
            ));
        }
        Ok(self
            .eigenvalues
            .iter()
            .zip(&self.harmonic)
            .map(|(&l, &h)| if h { 0.1 * lowest } else { l })
            .collect())
    }

    /// The reduced row `C̃_row U` (`d` values) of a sparse row over the field coefficients.
    pub fn reduce_row(&self, row: &[(usize, f64)]) -> Vec<f64> {
        let mut out = vec![0.0; self.len()];
        for &(j, a) in row {
            for (o, u) in out.iter_mut().zip(self.row(j)) {
                *o += a * u;
            }
        }
        out
    }

    /// The rows of `constraint` in reduced coordinates, `C̃_i U` (one `d`-vector per row);
    /// fails if a row addresses a field coefficient `≥ n1`.
    pub fn reduce_constraint(
        &self,
        constraint: &CompiledConstraint,
    ) -> Result<Vec<Vec<f64>>, DesignError> {
        let n = self.field_dimension();
        if let Some(&(j, _)) = constraint.rows.iter().flatten().find(|(j, _)| *j >= n) {
            return Err(DesignError::DimensionMismatch {
                what: "constraint row column (must be < n1)",
                expected: n,
                actual: j,
            });
        }
        Ok(constraint.rows.iter().map(|r| self.reduce_row(r)).collect())
    }

    /// `x = U v` (`n1` values, multithreaded): one dot product per coefficient.
    pub fn map(&self, coefficients: &[f64], field: &mut [f64]) -> Result<(), DesignError> {
        self.fields.map(coefficients, field)
    }

    /// A single-precision copy of `U` for the fast map `x = U v`.
    pub fn to_f32(&self) -> ReducedBasisF32 {
        RowMajorFields {
            rows: self.fields.rows.par_iter().map(|&x| x as f32).collect(),
            len: self.fields.len,
            field_dimension: self.fields.field_dimension,
        }
    }
}

impl<T: FieldScalar> RowMajorFields<T> {
    /// Number of basis fields `d`.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the basis has no field.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// `x = U v` (`n1` values, multithreaded): one dot product per coefficient, accumulated in
    /// `T` (for `f32`, relative error about `d · 6e-8` of `Σ|U_rk v_k|`).
    pub fn map(&self, coefficients: &[T], field: &mut [T]) -> Result<(), DesignError> {
        let d = self.len;
        check_map(d, self.field_dimension, coefficients.len(), field.len())?;
        field
            .par_chunks_mut(ROWS_PER_TASK)
            .zip(self.rows.par_chunks(ROWS_PER_TASK * d.max(1)))
            .for_each(|(out, block)| {
                for (x, row) in out.iter_mut().zip(block.chunks_exact(d.max(1))) {
                    *x = dot(row, coefficients);
                }
            });
        Ok(())
    }
}

fn check_map(d: usize, n: usize, coefficients: usize, field: usize) -> Result<(), DesignError> {
    if coefficients != d {
        return Err(DesignError::DimensionMismatch {
            what: "reduced coefficients",
            expected: d,
            actual: coefficients,
        });
    }
    if field != n {
        return Err(DesignError::DimensionMismatch {
            what: "field coefficients (n1)",
            expected: n,
            actual: field,
        });
    }
    Ok(())
}

/// Dot product with `T::LANES` independent accumulators (lets the compiler vectorise).
pub(crate) fn dot<T: FieldScalar>(a: &[T], b: &[T]) -> T {
    let mut acc = [T::default(); 8];
    let lanes = T::LANES;
    let (head, a_tail) = a.split_at(a.len() - a.len() % lanes);
    let (b_head, b_tail) = b.split_at(head.len());
    for (x, y) in head.chunks_exact(lanes).zip(b_head.chunks_exact(lanes)) {
        for k in 0..lanes {
            acc[k] = acc[k] + x[k] * y[k];
        }
    }
    let tail = a_tail
        .iter()
        .zip(b_tail)
        .fold(T::default(), |sum, (&x, &y)| sum + x * y);
    acc[..lanes].iter().fold(T::default(), |sum, &x| sum + x) + tail
}
