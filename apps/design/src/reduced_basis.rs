//! [`ReducedBasis`]: the eigenfields `U` stored row by row, with the eigenvalues, for the reduced
//! solvers — every row, or only the rows the constraints touch with the map `x = U v` through a
//! [`FieldBasis`] (a basis file read in blocks: a basis larger than memory), read once up front
//! or when a constraint first touches them (the interactive editor); and
//! [`RowMajorFields`], the row-major `U` in `f64` or `f32` with the one multithreaded map
//! `x = U v` both precisions share.

use crate::constraint::CompiledConstraint;
use crate::error::DesignError;
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, OnceLock};
use tvf_spectral::{FieldBasis, FieldFamily, SpectralBasis};

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
    fields: ReducedFields,
    eigenvalues: Vec<f64>,
    harmonic: Vec<bool>,
}

/// The rows of `U` a [`ReducedBasis`] holds.
#[derive(Debug, Clone)]
enum ReducedFields {
    /// Every row.
    All(RowMajorFields<f64>),
    /// Some rows, and the basis they came from for `x = U v`.
    Sampled(SampledRows),
    /// The rows read from a basis when a constraint first touches them.
    OnDemand(OnDemandRows),
}

/// Rows of the first `len` fields of a basis, each read when a constraint first touches it
/// ([`ReducedBasis::reduce_constraint`]) and kept.
#[derive(Clone)]
struct OnDemandRows {
    /// One slot per field coefficient (`n1`), filled when the row is read (`len` values).
    rows: Vec<OnceLock<Box<[f64]>>>,
    /// The basis (`x = U v` is its synthesis).
    basis: Arc<dyn FieldBasis>,
    /// Fields used: the first `len` of `basis`.
    len: usize,
}

impl std::fmt::Debug for OnDemandRows {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OnDemandRows")
            .field(
                "read",
                &self.rows.iter().filter(|r| r.get().is_some()).count(),
            )
            .field("field_dimension", &self.rows.len())
            .field("len", &self.len)
            .finish()
    }
}

/// Rows of `U` at some field coefficients, with the basis that maps coefficients to fields.
#[derive(Clone)]
struct SampledRows {
    /// Position in `rows` of the row of each sampled field coefficient.
    index: HashMap<usize, usize>,
    /// The sampled rows, `d` values each.
    rows: Vec<Vec<f64>>,
    /// The basis (`x = U v` is its synthesis).
    basis: Arc<dyn FieldBasis>,
}

impl std::fmt::Debug for SampledRows {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SampledRows")
            .field("rows", &self.rows.len())
            .field("field_dimension", &self.basis.field_dimension())
            .finish()
    }
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
        let harmonic = harmonic_flags(basis.families());
        Self::from_row_major(rows, n, basis.eigenvalues().to_vec(), harmonic)
    }

    /// A basis from row-major values (`field_dimension × d`), eigenvalues and harmonic flags
    /// (`d` each). Eigenvalues must be finite and non-negative; small ones are flagged harmonic as
    /// in [`ReducedBasis::from_spectral`].
    pub fn from_row_major(
        rows: Vec<f64>,
        field_dimension: usize,
        eigenvalues: Vec<f64>,
        harmonic: Vec<bool>,
    ) -> Result<Self, DesignError> {
        let d = eigenvalues.len();
        if rows.len() != field_dimension * d {
            return Err(DesignError::DimensionMismatch {
                what: "basis values (n1 × d)",
                expected: field_dimension * d,
                actual: rows.len(),
            });
        }
        let fields = ReducedFields::All(RowMajorFields {
            rows,
            len: d,
            field_dimension,
        });
        Self::with_spectrum(fields, eigenvalues, harmonic)
    }

    /// The rows of `basis` at the field coefficients the rows of `constraints` touch
    /// ([`ReducedBasis::touched_rows`]), read once, with `basis` mapping reduced coefficients to
    /// fields: a reduced basis whose memory is these rows, not `U`. The constraint rows `C̃ U`
    /// are the whole basis's bit for bit where `basis` gives the rows it holds (see
    /// [`FieldBasis::rows`]); `x = U v` is `basis`'s synthesis, equal to the row-major map's to
    /// round-off (another summation order). Constraints touching other rows are refused by
    /// [`ReducedBasis::reduce_constraint`].
    pub fn from_field_basis(
        basis: Arc<dyn FieldBasis>,
        constraints: &[CompiledConstraint],
    ) -> Result<Self, DesignError> {
        let touched = Self::touched_rows(constraints);
        let rows = basis
            .rows(&touched)
            .map_err(|e| DesignError::BadBasis(e.to_string()))?;
        let index = touched.iter().enumerate().map(|(k, &r)| (r, k)).collect();
        let harmonic = harmonic_flags(basis.families());
        let eigenvalues = basis.eigenvalues().to_vec();
        let fields = ReducedFields::Sampled(SampledRows { index, rows, basis });
        Self::with_spectrum(fields, eigenvalues, harmonic)
    }

    /// `basis` with no row read yet: each row is read when a constraint first touches it
    /// ([`ReducedBasis::reduce_constraint`], through [`FieldBasis::rows`]: the whole basis's
    /// rows bit for bit where the basis gives them so) and kept; `x = U v` is `basis`'s synthesis
    /// and the single-precision copy ([`ReducedBasis::to_f32`]) is formed from one visit of its
    /// fields. Memory: the rows read, not `U`.
    pub fn on_demand(basis: Arc<dyn FieldBasis>) -> Result<Self, DesignError> {
        let harmonic = harmonic_flags(basis.families());
        let eigenvalues = basis.eigenvalues().to_vec();
        let fields = ReducedFields::OnDemand(OnDemandRows {
            rows: (0..basis.field_dimension())
                .map(|_| OnceLock::new())
                .collect(),
            len: eigenvalues.len(),
            basis,
        });
        Self::with_spectrum(fields, eigenvalues, harmonic)
    }

    /// The first `d` fields (`1 ≤ d ≤ len`): a row-major copy of an in-memory basis, the same
    /// basis file read on demand, refused for a basis of some rows.
    pub fn first_fields(&self, d: usize) -> Result<Self, DesignError> {
        if d == 0 || d > self.len() {
            return Err(DesignError::BadBasis(format!(
                "{d} fields asked of a basis of {}",
                self.len()
            )));
        }
        let eigenvalues = self.eigenvalues[..d].to_vec();
        let harmonic = self.harmonic[..d].to_vec();
        match &self.fields {
            ReducedFields::All(fields) => {
                let n = fields.field_dimension;
                let mut rows = Vec::with_capacity(n * d);
                for r in 0..n {
                    rows.extend_from_slice(&self.row(r)[..d]);
                }
                Self::from_row_major(rows, n, eigenvalues, harmonic)
            }
            ReducedFields::OnDemand(on_demand) => {
                let rows = on_demand
                    .rows
                    .iter()
                    .map(|row| match row.get() {
                        Some(values) => OnceLock::from(Box::from(&values[..d])),
                        None => OnceLock::new(),
                    })
                    .collect();
                let fields = ReducedFields::OnDemand(OnDemandRows {
                    rows,
                    basis: on_demand.basis.clone(),
                    len: d,
                });
                Self::with_spectrum(fields, eigenvalues, harmonic)
            }
            ReducedFields::Sampled(_) => Err(DesignError::BadBasis(
                "a basis of the constraints' rows cannot be truncated".into(),
            )),
        }
    }

    /// Reads the rows `wanted` that a basis read on demand does not hold yet (nothing for the
    /// other kinds).
    fn read_missing_rows(&self, wanted: &[usize]) -> Result<(), DesignError> {
        let ReducedFields::OnDemand(on_demand) = &self.fields else {
            return Ok(());
        };
        let mut missing: Vec<usize> = wanted
            .iter()
            .copied()
            .filter(|&j| on_demand.rows[j].get().is_none())
            .collect();
        missing.sort_unstable();
        missing.dedup();
        if missing.is_empty() {
            return Ok(());
        }
        let rows = on_demand
            .basis
            .rows(&missing)
            .map_err(|e| DesignError::BadBasis(e.to_string()))?;
        for (&j, row) in missing.iter().zip(rows) {
            let _ = on_demand.rows[j].set(Box::from(&row[..on_demand.len]));
        }
        Ok(())
    }

    /// The field coefficients the rows of `constraints` touch, ascending, each once.
    pub fn touched_rows(constraints: &[CompiledConstraint]) -> Vec<usize> {
        let mut touched: Vec<usize> = constraints
            .iter()
            .flat_map(|c| c.rows.iter().flatten().map(|&(j, _)| j))
            .collect();
        touched.sort_unstable();
        touched.dedup();
        touched
    }

    /// A basis of `fields` with `eigenvalues` (finite, non-negative) and `harmonic` flags (`d`
    /// each); small eigenvalues are flagged harmonic as in [`ReducedBasis::from_spectral`].
    fn with_spectrum(
        fields: ReducedFields,
        eigenvalues: Vec<f64>,
        mut harmonic: Vec<bool>,
    ) -> Result<Self, DesignError> {
        if harmonic.len() != eigenvalues.len() {
            return Err(DesignError::DimensionMismatch {
                what: "harmonic flags",
                expected: eigenvalues.len(),
                actual: harmonic.len(),
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
            fields,
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
        match &self.fields {
            ReducedFields::All(fields) => fields.field_dimension,
            ReducedFields::Sampled(sampled) => sampled.basis.field_dimension(),
            ReducedFields::OnDemand(on_demand) => on_demand.rows.len(),
        }
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
    ///
    /// # Panics
    /// If the basis holds only some rows ([`ReducedBasis::from_field_basis`]) and `r` is not one
    /// of them, or reads rows on demand ([`ReducedBasis::on_demand`]) and no constraint touching
    /// `r` was reduced yet (a programming error: [`ReducedBasis::reduce_constraint`] checks or
    /// reads its rows).
    pub fn row(&self, r: usize) -> &[f64] {
        match &self.fields {
            ReducedFields::All(fields) => {
                let d = self.len();
                &fields.rows[r * d..(r + 1) * d]
            }
            ReducedFields::Sampled(sampled) => &sampled.rows[sampled.index[&r]],
            ReducedFields::OnDemand(on_demand) => on_demand.rows[r]
                .get()
                .unwrap_or_else(|| panic!("row {r} of the basis was not read")),
        }
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
    /// fails if a row addresses a field coefficient `≥ n1`. A basis read on demand reads the
    /// rows it does not hold yet.
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
        if let ReducedFields::Sampled(sampled) = &self.fields {
            let held = |j: &usize| sampled.index.contains_key(j);
            if let Some(&(j, _)) = constraint.rows.iter().flatten().find(|(j, _)| !held(j)) {
                return Err(DesignError::BadBasis(format!(
                    "constraint '{}' touches field coefficient {j}, whose row of the basis was                      not read (the basis holds the rows of the constraints it was made for)",
                    constraint.id
                )));
            }
        }
        let touched: Vec<usize> = constraint.rows.iter().flatten().map(|&(j, _)| j).collect();
        self.read_missing_rows(&touched)?;
        Ok(constraint.rows.iter().map(|r| self.reduce_row(r)).collect())
    }

    /// `x = U v` (`n1` values, multithreaded): one dot product per coefficient, or the
    /// synthesis of the basis the rows were read from.
    pub fn map(&self, coefficients: &[f64], field: &mut [f64]) -> Result<(), DesignError> {
        let basis = match &self.fields {
            ReducedFields::All(fields) => return fields.map(coefficients, field),
            ReducedFields::Sampled(sampled) => &sampled.basis,
            ReducedFields::OnDemand(on_demand) => &on_demand.basis,
        };
        check_map(
            self.len(),
            self.field_dimension(),
            coefficients.len(),
            field.len(),
        )?;
        // The fields beyond the first `d` (a truncated basis read on demand) weigh zero.
        let mut all = coefficients.to_vec();
        all.resize(basis.len(), 0.0);
        let mapped = basis
            .reconstruct(&all)
            .map_err(|e| DesignError::BadBasis(e.to_string()))?;
        field.copy_from_slice(&mapped);
        Ok(())
    }

    /// A single-precision copy of `U` for the fast map `x = U v` (each value rounded to nearest);
    /// of a basis read on demand, formed from one visit of its fields (one pass over a basis
    /// file, which is not held in `f64`); refused for a basis that holds only some rows.
    pub fn to_f32(&self) -> Result<ReducedBasisF32, DesignError> {
        match &self.fields {
            ReducedFields::All(fields) => Ok(RowMajorFields {
                rows: fields.rows.par_iter().map(|&x| x as f32).collect(),
                len: fields.len,
                field_dimension: fields.field_dimension,
            }),
            ReducedFields::Sampled(_) => Err(DesignError::BadBasis(
                "a basis of the constraints' rows has no row-major copy".into(),
            )),
            ReducedFields::OnDemand(on_demand) => {
                let (n, d) = (on_demand.rows.len(), on_demand.len);
                // Fields are visited from several threads: each stores its column's bits.
                let values: Vec<AtomicU32> = (0..n * d).map(|_| AtomicU32::new(0)).collect();
                on_demand
                    .basis
                    .visit_fields(&|i, field| {
                        if i < d {
                            for (r, &x) in field.iter().enumerate() {
                                values[r * d + i].store((x as f32).to_bits(), Ordering::Relaxed);
                            }
                        }
                    })
                    .map_err(|e| DesignError::BadBasis(e.to_string()))?;
                Ok(RowMajorFields {
                    rows: values
                        .into_iter()
                        .map(|v| f32::from_bits(v.into_inner()))
                        .collect(),
                    len: d,
                    field_dimension: n,
                })
            }
        }
    }
}

/// Whether each field of `families` is harmonic.
fn harmonic_flags(families: &[FieldFamily]) -> Vec<bool> {
    families
        .iter()
        .map(|f| *f == FieldFamily::Harmonic)
        .collect()
}

impl<T: FieldScalar> RowMajorFields<T> {
    /// The values, row by row (`n × d`).
    pub fn values(&self) -> &[T] {
        &self.rows
    }

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
