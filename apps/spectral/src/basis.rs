//! [`SpectralBasis`]: an `M_X`-orthonormal set of eigenfields of the Hodge–Laplacian.

use crate::{BasisReport, EigenfunctionBasis};
use faer::{Col, Mat, MatRef};
use rayon::prelude::*;
use thiserror::Error;
use tvf_core::discretization::Mass;

/// The family a basis field belongs to in the Hodge decomposition.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FieldFamily {
    /// In the kernel of the Hodge–Laplacian (eigenvalue 0); `2g` of them on a closed mesh.
    Harmonic,
    /// A normalised gradient of a potential eigenfunction, `Φ = d0 φ / √λ` (curl-free).
    Integrable,
    /// A normalised co-gradient of a co-potential eigenfunction, `Ψ = J G ψ / √μ` (divergence-free).
    Cointegrable,
}

impl FieldFamily {
    /// Lower-case name used in files and JSON: `harmonic`, `integrable`, `cointegrable`.
    pub fn name(self) -> &'static str {
        match self {
            FieldFamily::Harmonic => "harmonic",
            FieldFamily::Integrable => "integrable",
            FieldFamily::Cointegrable => "cointegrable",
        }
    }
}

/// Inconsistent data handed to [`SpectralBasis::new`] or to its methods.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SpectralBasisError {
    /// Two lengths that must agree do not.
    #[error("{what}: expected length {expected}, got {actual}")]
    LengthMismatch {
        /// What was being checked.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Actual length.
        actual: usize,
    },
    /// Eigenvalues must be finite, non-negative and ascending.
    #[error(
        "eigenvalue {index} is {value}: eigenvalues must be finite, non-negative and ascending"
    )]
    BadEigenvalue {
        /// Position in the basis.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A basis read from its file block by block could not read a block.
    #[error("{}: cannot read the basis file: {reason}", path.display())]
    Read {
        /// The basis file.
        path: std::path::PathBuf,
        /// What went wrong.
        reason: String,
    },
}

/// `d` eigenfields of the Hodge–Laplacian `L` of one discretization, `M_X`-orthonormal.
///
/// Shapes: `fields` is `n1 × d` (column `i` is field `i` in the complex's field coefficients),
/// `eigenvalues` and `families` have `d` entries, ascending in eigenvalue, `field_mass` is the
/// complex's `M1` (`n1 × n1`, diagonal or sparse). `L U = U Λ` and `Uᵀ M1 U = I` hold to solver
/// accuracy.
#[derive(Debug, Clone)]
pub struct SpectralBasis {
    eigenvalues: Vec<f64>,
    families: Vec<FieldFamily>,
    fields: Mat<f64>,
    field_mass: Mass,
    /// Optional `f32` copy of `fields` (same shape) for fast reconstruction.
    fields_f32: Option<Mat<f32>>,
    /// Optional compact form (eigenfunctions) of the same basis.
    eigenfunctions: Option<EigenfunctionBasis>,
    /// How the basis was computed (absent for a basis loaded from a file or built by hand).
    report: Option<BasisReport>,
}

impl SpectralBasis {
    /// Assembles a basis from its parts, checking shapes and the ordering of eigenvalues.
    pub fn new(
        eigenvalues: Vec<f64>,
        families: Vec<FieldFamily>,
        fields: Mat<f64>,
        field_mass: Mass,
    ) -> Result<Self, SpectralBasisError> {
        let d = eigenvalues.len();
        check_length("families", d, families.len())?;
        check_length("basis columns", d, fields.ncols())?;
        check_length("field mass", fields.nrows(), field_mass.len())?;
        check_eigenvalues(&eigenvalues)?;
        Ok(Self {
            eigenvalues,
            families,
            fields,
            field_mass,
            fields_f32: None,
            eigenfunctions: None,
            report: None,
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
        self.fields.nrows()
    }

    /// Eigenvalues `λ_i` of `L`, ascending, `d` entries (units 1/length²).
    pub fn eigenvalues(&self) -> &[f64] {
        &self.eigenvalues
    }

    /// Frequencies `√λ_i`, `d` entries.
    pub fn frequencies(&self) -> Vec<f64> {
        self.eigenvalues.iter().map(|l| l.sqrt()).collect()
    }

    /// Family of each basis field, `d` entries.
    pub fn families(&self) -> &[FieldFamily] {
        &self.families
    }

    /// The fields `U`, `n1 × d`.
    pub fn fields(&self) -> MatRef<'_, f64> {
        self.fields.as_ref()
    }

    /// The field mass `M1` (`n1 × n1`).
    pub fn field_mass(&self) -> &Mass {
        &self.field_mass
    }

    /// Fourier coefficients `Uᵀ M1 v` of a field `v` (`n1` entries), `d` entries.
    pub fn coefficients(&self, field: &[f64]) -> Result<Vec<f64>, SpectralBasisError> {
        check_length("field", self.field_dimension(), field.len())?;
        let weighted = match self.field_mass.diagonal_values() {
            Some(mass) => Col::from_fn(field.len(), |r| mass[r] * field[r]),
            None => {
                let weighted = self.field_mass.apply(field);
                Col::from_fn(field.len(), |r| weighted[r])
            }
        };
        let coefficients = self.fields.transpose() * &weighted;
        Ok((0..self.len()).map(|i| coefficients[i]).collect())
    }

    /// The field `U c` for coefficients `c` (`d` entries), `n1` entries.
    pub fn reconstruct(&self, coefficients: &[f64]) -> Result<Vec<f64>, SpectralBasisError> {
        check_length("coefficients", self.len(), coefficients.len())?;
        Ok(combine_columns(self.fields.as_ref(), coefficients))
    }

    /// Number of basis fields of one family.
    pub fn count(&self, family: FieldFamily) -> usize {
        self.families.iter().filter(|&&f| f == family).count()
    }

    /// Stores an `f32` copy of the fields (`n1 × d`, rounded to nearest), used by
    /// [`reconstruct_f32`](Self::reconstruct_f32). Costs half the memory of the fields.
    pub fn store_single_precision_copy(&mut self) {
        let f = &self.fields;
        self.fields_f32 = Some(Mat::from_fn(f.nrows(), f.ncols(), |i, j| f[(i, j)] as f32));
    }

    /// The `f32` copy of the fields, if stored.
    pub fn fields_f32(&self) -> Option<MatRef<'_, f32>> {
        self.fields_f32.as_ref().map(|m| m.as_ref())
    }

    /// The field `U c` (`n1` entries) computed from the `f32` copy of `U` (accumulated in `f64`):
    /// half the memory traffic of [`reconstruct`](Self::reconstruct), relative error about
    /// `1e-7`. Falls back to the `f64` fields if no copy is stored.
    pub fn reconstruct_f32(&self, coefficients: &[f64]) -> Result<Vec<f64>, SpectralBasisError> {
        let Some(single) = &self.fields_f32 else {
            return self.reconstruct(coefficients);
        };
        check_length("coefficients", self.len(), coefficients.len())?;
        Ok(combine_columns(single.as_ref(), coefficients))
    }

    /// The compact form of this basis (eigenfunctions), if it was kept
    /// ([`crate::BasisRequest::keep_eigenfunctions`]).
    pub fn eigenfunctions(&self) -> Option<&EigenfunctionBasis> {
        self.eigenfunctions.as_ref()
    }

    /// Removes the compact form from this basis and returns it, if it was kept.
    pub fn take_eigenfunctions(&mut self) -> Option<EigenfunctionBasis> {
        self.eigenfunctions.take()
    }

    /// Attaches the compact form of the same basis (same order and eigenvalues).
    pub fn attach_eigenfunctions(&mut self, eigenfunctions: EigenfunctionBasis) {
        self.eigenfunctions = Some(eigenfunctions);
    }

    /// How the basis was computed, if it was computed by [`crate::compute_basis`].
    pub fn report(&self) -> Option<&BasisReport> {
        self.report.as_ref()
    }

    /// Attaches a computation report.
    pub fn attach_report(&mut self, report: BasisReport) {
        self.report = Some(report);
    }

    /// `M1` inner product `aᵀ M1 b` of two fields (`n1` entries each).
    pub fn inner_product(&self, a: &[f64], b: &[f64]) -> f64 {
        match self.field_mass.diagonal_values() {
            Some(mass) => a.iter().zip(b).zip(mass).map(|((x, y), m)| x * m * y).sum(),
            None => self.field_mass.inner(a, b),
        }
    }
}

/// Rows of a matrix processed together by one thread in [`combine_columns`]: 4096 rows of `f64`
/// (32 KiB) stay in the L1/L2 cache while every column adds its slice.
const ROW_CHUNK: usize = 4096;

/// `Σ_i c_i U[:, i]` accumulated in `f64` (`U` is `n × d`, `c` has `d` entries, the result `n`),
/// split into row chunks over threads so that `U` is streamed once; zero coefficients are skipped.
fn combine_columns<T: Copy + Into<f64> + Sync>(
    columns: MatRef<'_, T>,
    coefficients: &[f64],
) -> Vec<f64> {
    let mut field = vec![0.0; columns.nrows()];
    field
        .par_chunks_mut(ROW_CHUNK)
        .enumerate()
        .for_each(|(chunk, out)| {
            let start = chunk * ROW_CHUNK;
            for (i, &c) in coefficients.iter().enumerate() {
                if c != 0.0 {
                    let column = columns.col(i);
                    for (k, value) in out.iter_mut().enumerate() {
                        *value += c * column[start + k].into();
                    }
                }
            }
        });
    field
}

/// `Ok` when `actual == expected`, else a [`SpectralBasisError::LengthMismatch`] naming `what`.
/// Checks that `eigenvalues` are finite, non-negative and ascending.
pub(crate) fn check_eigenvalues(eigenvalues: &[f64]) -> Result<(), SpectralBasisError> {
    for (index, &value) in eigenvalues.iter().enumerate() {
        let ascending = index == 0 || value >= eigenvalues[index - 1];
        if !value.is_finite() || value < 0.0 || !ascending {
            return Err(SpectralBasisError::BadEigenvalue { index, value });
        }
    }
    Ok(())
}

pub(crate) fn check_length(
    what: &'static str,
    expected: usize,
    actual: usize,
) -> Result<(), SpectralBasisError> {
    if expected == actual {
        Ok(())
    } else {
        Err(SpectralBasisError::LengthMismatch {
            what,
            expected,
            actual,
        })
    }
}
