//! [`ReducedBasis`]: the eigenfields `U` stored row by row, with the eigenvalues, for the reduced
//! solvers; and the multithreaded maps `x = U v` in `f64` and `f32`.

use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use rayon::prelude::*;
use tvf_spectral::{FieldFamily, SpectralBasis};

/// Rows per parallel task in the maps `x = U v`.
const ROWS_PER_TASK: usize = 2048;

/// `d` basis fields `U` (`2F × d`, `Uᵀ M_X U = I`) stored **row-major** (row `r` = the `d`
/// values of coefficient `r` across the basis), with eigenvalues `λ_i` of the Hodge–Laplacian
/// (units 1/length²) and a harmonic flag per field.
///
/// Row-major storage makes both reduced-solver hot paths contiguous: a constraint row
/// `C = C̃ U` reads only the few rows of `U` its face touches, and `x = U v` is one dot product
/// per output coefficient, streaming `U` exactly once.
#[derive(Debug, Clone)]
pub struct ReducedBasis {
    rows: Vec<f64>,
    field_dimension: usize,
    eigenvalues: Vec<f64>,
    harmonic: Vec<bool>,
}

/// `U` in single precision (row-major), for the fast map `x = U v` (half the memory traffic).
#[derive(Debug, Clone)]
pub struct ReducedBasisF32 {
    rows: Vec<f32>,
    len: usize,
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
                what: "basis values (2F × d)",
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
            rows,
            field_dimension,
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

    /// Dimension `2F` of the field space.
    pub fn field_dimension(&self) -> usize {
        self.field_dimension
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
        &self.rows[r * d..(r + 1) * d]
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
    /// fails if a row addresses a field coefficient `≥ 2F`.
    pub fn reduce_constraint(
        &self,
        constraint: &CompiledConstraint,
    ) -> Result<Vec<Vec<f64>>, DesignError> {
        let n = self.field_dimension();
        if let Some(&(j, _)) = constraint.rows.iter().flatten().find(|(j, _)| *j >= n) {
            return Err(DesignError::DimensionMismatch {
                what: "constraint row column (must be < 2F)",
                expected: n,
                actual: j,
            });
        }
        Ok(constraint.rows.iter().map(|r| self.reduce_row(r)).collect())
    }

    /// `x = U v` (`2F` values, multithreaded): one dot product per coefficient.
    pub fn map(&self, coefficients: &[f64], field: &mut [f64]) -> Result<(), DesignError> {
        self.check_map(coefficients.len(), field.len())?;
        let d = self.len();
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

    /// Sum of all entries of `U`, multithreaded: reads `U` once, the memory-streaming reference
    /// the map `x = U v` is measured against.
    pub fn stream_sum(&self) -> f64 {
        self.rows
            .par_chunks(ROWS_PER_TASK * self.len().max(1))
            .map(lane_sum)
            .sum()
    }

    /// A single-precision copy of `U` for [`ReducedBasisF32::map`].
    pub fn to_f32(&self) -> ReducedBasisF32 {
        ReducedBasisF32 {
            rows: self.rows.par_iter().map(|&x| x as f32).collect(),
            len: self.len(),
        }
    }

    fn check_map(&self, coefficients: usize, field: usize) -> Result<(), DesignError> {
        check_map(self.len(), self.field_dimension, coefficients, field)
    }
}

impl ReducedBasisF32 {
    /// Number of basis fields `d`.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the basis has no field.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// `x = U v` in single precision (`2F` values, multithreaded; `f32` accumulation over `d`
    /// terms, relative error about `d · 6e-8` of `Σ|U_rk v_k|`).
    pub fn map(&self, coefficients: &[f32], field: &mut [f32]) -> Result<(), DesignError> {
        let d = self.len;
        check_map(
            d,
            self.rows.len() / d.max(1),
            coefficients.len(),
            field.len(),
        )?;
        field
            .par_chunks_mut(ROWS_PER_TASK)
            .zip(self.rows.par_chunks(ROWS_PER_TASK * d.max(1)))
            .for_each(|(out, block)| {
                for (x, row) in out.iter_mut().zip(block.chunks_exact(d.max(1))) {
                    *x = dot_f32(row, coefficients);
                }
            });
        Ok(())
    }

    /// Sum of all entries (the streaming reference for the `f32` map).
    pub fn stream_sum(&self) -> f32 {
        self.rows
            .par_chunks(ROWS_PER_TASK * self.len.max(1))
            .map(|c| {
                let mut acc = [0.0f32; 8];
                let (head, tail) = c.split_at(c.len() - c.len() % 8);
                for x in head.chunks_exact(8) {
                    for k in 0..8 {
                        acc[k] += x[k];
                    }
                }
                acc.iter().sum::<f32>() + tail.iter().sum::<f32>()
            })
            .sum()
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
            what: "field coefficients (2F)",
            expected: n,
            actual: field,
        });
    }
    Ok(())
}

/// Dot product with four independent accumulators (lets the compiler vectorise).
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (a4, ar) = a.split_at(a.len() - a.len() % 4);
    let (b4, br) = b.split_at(a4.len());
    for (x, y) in a4.chunks_exact(4).zip(b4.chunks_exact(4)) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f64 = ar.iter().zip(br).map(|(x, y)| x * y).sum();
    acc[0] + acc[1] + acc[2] + acc[3] + tail
}

/// Sum with four independent accumulators (vectorisable, so it runs at memory speed).
fn lane_sum(a: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (head, tail) = a.split_at(a.len() - a.len() % 4);
    for x in head.chunks_exact(4) {
        for k in 0..4 {
            acc[k] += x[k];
        }
    }
    acc[0] + acc[1] + acc[2] + acc[3] + tail.iter().sum::<f64>()
}

/// `f32` dot product with eight independent accumulators.
fn dot_f32(a: &[f32], b: &[f32]) -> f32 {
    let mut acc = [0.0f32; 8];
    let (a8, ar) = a.split_at(a.len() - a.len() % 8);
    let (b8, br) = b.split_at(a8.len());
    for (x, y) in a8.chunks_exact(8).zip(b8.chunks_exact(8)) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    acc.iter().sum::<f32>() + ar.iter().zip(br).map(|(x, y)| x * y).sum::<f32>()
}
