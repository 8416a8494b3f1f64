//! [`EigenfunctionBasis`]: the Fourier basis stored as eigenfunctions (half the memory of the
//! dense fields), turned into fields through the complex's gradients `d0` and `−M1⁻¹ d1ᵀ`.

use crate::basis::{check_eigenvalues, check_length};
use crate::{FieldFamily, SpectralBasisError};
use faer::reborrow::ReborrowMut;
use faer::{Col, ColRef, Mat, MatRef};
use tvf_core::discretization::sparse::{mul_transpose_vec, mul_vec};
use tvf_core::discretization::{HodgeComplex, HodgeOperators, LinearOperator};

/// The basis of [`crate::compute_basis`] in compact form: integrable fields as potentials,
/// co-integrable fields as co-potentials, harmonic fields as fields.
///
/// With `φ̃_i` the columns of [`potentials`](Self::potentials) (`n0 × a`) and `ψ̃_j` those of
/// [`co_potentials`](Self::co_potentials) (`n2 × b`), the fields are
/// `Φ_i = d0 φ̃_i` and `Ψ_j = −M1⁻¹ d1ᵀ ψ̃_j`, `M1`-unit: each stored function is the
/// `M0`-normalised eigenfunction divided by `√λ` (so `φ̃ = φ / √λ`). The harmonic fields are
/// stored densely (`n1 × h`). An integrable field costs `n0` numbers, a co-integrable one `n2`;
/// for face fields on a closed mesh `n0 + n2 = V + E ≈ 2F`, half of the `4F` of a dense pair.
///
/// All methods that produce or consume fields need the complex the basis was computed for.
#[derive(Debug, Clone)]
pub struct EigenfunctionBasis {
    eigenvalues: Vec<f64>,
    families: Vec<FieldFamily>,
    /// Column of each basis field inside its family's matrix.
    slots: Vec<usize>,
    potentials: Mat<f64>,
    co_potentials: Mat<f64>,
    harmonic: Mat<f64>,
}

impl EigenfunctionBasis {
    /// Assembles a compact basis. `entries` lists, in basis order (ascending eigenvalue), each
    /// field's eigenvalue, family and column in that family's matrix.
    pub(crate) fn new(
        entries: Vec<(f64, FieldFamily, usize)>,
        potentials: Mat<f64>,
        co_potentials: Mat<f64>,
        harmonic: Mat<f64>,
    ) -> Self {
        Self {
            eigenvalues: entries.iter().map(|e| e.0).collect(),
            families: entries.iter().map(|e| e.1).collect(),
            slots: entries.iter().map(|e| e.2).collect(),
            potentials,
            co_potentials,
            harmonic,
        }
    }

    /// Assembles a compact basis from its stored form: `eigenvalues` and `families` in basis
    /// order, and each family's matrix with its columns in the order the family's fields appear
    /// in the basis (as [`family_slots`](Self::family_slots) lists them). Checks the eigenvalues
    /// and that each matrix has one column per field of its family.
    pub fn from_columns(
        eigenvalues: Vec<f64>,
        families: Vec<FieldFamily>,
        potentials: Mat<f64>,
        co_potentials: Mat<f64>,
        harmonic: Mat<f64>,
    ) -> Result<Self, SpectralBasisError> {
        check_length("families", eigenvalues.len(), families.len())?;
        check_eigenvalues(&eigenvalues)?;
        let count = |family| families.iter().filter(|&&f| f == family).count();
        check_length(
            "potential columns (integrable fields)",
            count(FieldFamily::Integrable),
            potentials.ncols(),
        )?;
        check_length(
            "co-potential columns (co-integrable fields)",
            count(FieldFamily::Cointegrable),
            co_potentials.ncols(),
        )?;
        check_length(
            "harmonic columns",
            count(FieldFamily::Harmonic),
            harmonic.ncols(),
        )?;
        let mut next = [0usize; 3];
        let slots = families
            .iter()
            .map(|&family| {
                let counter = &mut next[family_index(family)];
                *counter += 1;
                *counter - 1
            })
            .collect();
        Ok(Self {
            eigenvalues,
            families,
            slots,
            potentials,
            co_potentials,
            harmonic,
        })
    }

    /// The columns of `family`'s matrix that hold its fields, in the order the fields appear in
    /// the basis.
    pub fn family_slots(&self, family: FieldFamily) -> Vec<usize> {
        self.families
            .iter()
            .zip(&self.slots)
            .filter(|(&f, _)| f == family)
            .map(|(_, &slot)| slot)
            .collect()
    }

    /// Number of basis fields `d`.
    pub fn len(&self) -> usize {
        self.eigenvalues.len()
    }

    /// Whether the basis has no field.
    pub fn is_empty(&self) -> bool {
        self.eigenvalues.is_empty()
    }

    /// Eigenvalues, ascending (`d` entries, 1/length²).
    pub fn eigenvalues(&self) -> &[f64] {
        &self.eigenvalues
    }

    /// Family of each basis field (`d` entries).
    pub fn families(&self) -> &[FieldFamily] {
        &self.families
    }

    /// Scaled potential eigenfunctions `φ̃` (`n0 × a`, pointwise nodal values), columns in
    /// ascending eigenvalue.
    pub fn potentials(&self) -> MatRef<'_, f64> {
        self.potentials.as_ref()
    }

    /// Scaled co-potential eigenfunctions `ψ̃` (`n2 × b`), columns in ascending eigenvalue.
    pub fn co_potentials(&self) -> MatRef<'_, f64> {
        self.co_potentials.as_ref()
    }

    /// Harmonic fields (`n1 × h`, `M1`-orthonormal).
    pub fn harmonic_fields(&self) -> MatRef<'_, f64> {
        self.harmonic.as_ref()
    }

    /// Bytes held by the three matrices.
    pub fn memory_bytes(&self) -> usize {
        8 * (self.potentials.nrows() * self.potentials.ncols()
            + self.co_potentials.nrows() * self.co_potentials.ncols()
            + self.harmonic.nrows() * self.harmonic.ncols())
    }

    /// Checks that `complex` has the shapes this basis was computed with.
    pub(crate) fn check_complex<H: HodgeComplex + ?Sized>(
        &self,
        complex: &H,
    ) -> Result<(), SpectralBasisError> {
        check_length(
            "harmonic field rows (n1)",
            complex.field_dimension(),
            self.harmonic.nrows(),
        )?;
        check_length(
            "potential rows (n0)",
            complex.potential_dimension(),
            self.potentials.nrows(),
        )?;
        check_length(
            "co-potential rows (n2)",
            complex.co_potential_dimension(),
            self.co_potentials.nrows(),
        )
    }

    /// Basis field `index` as a dense field (`n1` pointwise coefficients).
    pub fn field<H: HodgeComplex + ?Sized>(&self, complex: &H, index: usize) -> Vec<f64> {
        let slot = self.slots[index];
        match self.families[index] {
            FieldFamily::Integrable => {
                complex.gradient_field(&column(self.potentials.as_ref(), slot))
            }
            FieldFamily::Cointegrable => {
                complex.co_gradient_field(&column(self.co_potentials.as_ref(), slot))
            }
            FieldFamily::Harmonic => column(self.harmonic.as_ref(), slot),
        }
    }

    /// Fourier coefficients `Uᵀ M1 v` of a field `v` (`n1` entries) by sparse products:
    /// `α = φ̃ᵀ d0ᵀ M1 v`, `β = −ψ̃ᵀ d1 v` (since the co-gradient is `−M1⁻¹ d1ᵀ`), `γ = Γᵀ M1 v`.
    /// Returns `d` coefficients in basis order.
    pub fn coefficients<H: HodgeComplex + ?Sized>(
        &self,
        complex: &H,
        field: &[f64],
    ) -> Result<Vec<f64>, SpectralBasisError> {
        check_length("field", complex.field_dimension(), field.len())?;
        self.check_complex(complex)?;
        let weighted = complex.m1().apply(field);
        let divergence = mul_transpose_vec(complex.d0(), &weighted);
        let curl: Vec<f64> = mul_vec(complex.d1(), field).iter().map(|x| -x).collect();
        let alpha = transpose_times(self.potentials.as_ref(), &divergence);
        let beta = transpose_times(self.co_potentials.as_ref(), &curl);
        let gamma = transpose_times(self.harmonic.as_ref(), &weighted);
        Ok((0..self.len())
            .map(|i| match self.families[i] {
                FieldFamily::Integrable => alpha[self.slots[i]],
                FieldFamily::Cointegrable => beta[self.slots[i]],
                FieldFamily::Harmonic => gamma[self.slots[i]],
            })
            .collect())
    }

    /// The field `Σ c_i U_i` (`n1` entries) from `d` coefficients: `d0 (φ̃ α) − M1⁻¹ d1ᵀ (ψ̃ β) +
    /// Γ γ`.
    pub fn reconstruct<H: HodgeComplex + ?Sized>(
        &self,
        complex: &H,
        coefficients: &[f64],
    ) -> Result<Vec<f64>, SpectralBasisError> {
        check_length("coefficients", self.len(), coefficients.len())?;
        self.check_complex(complex)?;
        let mut alpha = Col::<f64>::zeros(self.potentials.ncols());
        let mut beta = Col::<f64>::zeros(self.co_potentials.ncols());
        let mut gamma = Col::<f64>::zeros(self.harmonic.ncols());
        for (i, &c) in coefficients.iter().enumerate() {
            match self.families[i] {
                FieldFamily::Integrable => alpha[self.slots[i]] = c,
                FieldFamily::Cointegrable => beta[self.slots[i]] = c,
                FieldFamily::Harmonic => gamma[self.slots[i]] = c,
            }
        }
        let potential = &self.potentials * &alpha;
        let co_potential = &self.co_potentials * &beta;
        let harmonic = &self.harmonic * &gamma;
        let exact = complex.gradient_field(&col_vec(&potential));
        let co_exact = complex.co_gradient_field(&col_vec(&co_potential));
        Ok(exact
            .iter()
            .zip(&co_exact)
            .enumerate()
            .map(|(r, (a, b))| a + b + harmonic[r])
            .collect())
    }

    /// The basis fields `range` as dense fields (`n1` values each), built in parallel from the
    /// gradients `d0` and `−M1⁻¹ d1ᵀ`.
    pub fn field_columns<H: HodgeComplex + ?Sized>(
        &self,
        complex: &H,
        range: std::ops::Range<usize>,
    ) -> Vec<Vec<f64>> {
        use rayon::prelude::*;
        let (d0, co_gradient) = (complex.d0(), complex.co_gradient());
        range
            .into_par_iter()
            .map(|i| self.field_with(d0, co_gradient, i))
            .collect()
    }

    /// The dense fields `U` (`n1 × d`), column `i` = [`field`](Self::field)`(i)`, formed in
    /// parallel, each straight into its column. Where the co-gradient is not a sparse matrix
    /// (a non-diagonal `M1`), the co-integrable fields are formed first, all at once, by one
    /// block solve with `M1`.
    pub fn dense_fields<H: HodgeComplex + ?Sized>(&self, complex: &H) -> Mat<f64> {
        use rayon::prelude::*;
        let (d0, co_gradient) = (complex.d0(), complex.co_gradient());
        let mut fields = Mat::zeros(complex.field_dimension(), self.len());
        if !co_gradient.is_sparse() {
            let co_exact = co_gradient.apply_block(self.co_potentials.as_ref());
            for i in 0..self.len() {
                let slot = self.slots[i];
                match self.families[i] {
                    FieldFamily::Integrable => {
                        let stored = self.stored_column(i);
                        let values = mul_vec(d0, &stored);
                        fields.col_mut(i).copy_from(ColRef::from_slice(&values));
                    }
                    FieldFamily::Cointegrable => fields.col_mut(i).copy_from(co_exact.col(slot)),
                    FieldFamily::Harmonic => fields.col_mut(i).copy_from(self.harmonic.col(slot)),
                }
            }
            return fields;
        }
        fields
            .par_col_iter_mut()
            .enumerate()
            .for_each(
                |(i, mut column)| match column.rb_mut().try_as_col_major_mut() {
                    Some(target) => {
                        let stored = self.stored_column(i);
                        field_of_stored_into(
                            d0,
                            co_gradient,
                            self.families[i],
                            &stored,
                            target.as_slice_mut(),
                        );
                    }
                    None => {
                        let values = self.field_with(d0, co_gradient, i);
                        column.copy_from(ColRef::from_slice(&values));
                    }
                },
            );
        fields
    }

    /// The stored column (potential, co-potential or harmonic field) of basis field `i`.
    fn stored_column(&self, i: usize) -> std::borrow::Cow<'_, [f64]> {
        let slot = self.slots[i];
        let stored = match self.families[i] {
            FieldFamily::Integrable => self.potentials.col(slot),
            FieldFamily::Cointegrable => self.co_potentials.col(slot),
            FieldFamily::Harmonic => self.harmonic.col(slot),
        };
        match stored.try_as_col_major() {
            Some(contiguous) => std::borrow::Cow::Borrowed(contiguous.as_slice()),
            None => std::borrow::Cow::Owned(stored.iter().copied().collect()),
        }
    }

    /// Basis field `i` (`n1` values) from the gradient `d0` and the co-gradient `−M1⁻¹ d1ᵀ`.
    fn field_with(
        &self,
        d0: &sprs::CsMat<f64>,
        co_gradient: &LinearOperator,
        i: usize,
    ) -> Vec<f64> {
        field_of_stored(d0, co_gradient, self.families[i], &self.stored_column(i))
    }
}

/// The field (`n1` values) of one stored column of a compact basis: `d0 φ̃` for a potential,
/// `−M1⁻¹ d1ᵀ ψ̃` for a co-potential, the column itself for a harmonic field.
pub(crate) fn field_of_stored(
    d0: &sprs::CsMat<f64>,
    co_gradient: &LinearOperator,
    family: FieldFamily,
    stored: &[f64],
) -> Vec<f64> {
    let mut field = vec![0.0; d0.rows()];
    field_of_stored_into(d0, co_gradient, family, stored, &mut field);
    field
}

/// [`field_of_stored`] written into `field` (`n1` values).
pub(crate) fn field_of_stored_into(
    d0: &sprs::CsMat<f64>,
    co_gradient: &LinearOperator,
    family: FieldFamily,
    stored: &[f64],
    field: &mut [f64],
) {
    let operator = match family {
        FieldFamily::Integrable => d0,
        FieldFamily::Cointegrable => match co_gradient.as_sparse() {
            Some(sparse) => sparse,
            None => {
                field.copy_from_slice(&co_gradient.apply(stored));
                return;
            }
        },
        FieldFamily::Harmonic => {
            field.copy_from_slice(stored);
            return;
        }
    };
    if operator.is_csr() {
        for (value, row) in field.iter_mut().zip(operator.outer_iterator()) {
            *value = row.iter().map(|(j, a)| a * stored[j]).sum();
        }
    } else {
        field.copy_from_slice(&mul_vec(operator, stored));
    }
}

/// Position of `family` in per-family arrays: integrable, co-integrable, harmonic.
fn family_index(family: FieldFamily) -> usize {
    match family {
        FieldFamily::Integrable => 0,
        FieldFamily::Cointegrable => 1,
        FieldFamily::Harmonic => 2,
    }
}

/// Fields formed at a time by the streaming writer of basis files (enough to keep every core
/// busy, little memory).
pub const FIELD_CHUNK: usize = 64;

fn column(m: MatRef<'_, f64>, j: usize) -> Vec<f64> {
    (0..m.nrows()).map(|i| m[(i, j)]).collect()
}

fn col_vec(c: &Col<f64>) -> Vec<f64> {
    (0..c.nrows()).map(|i| c[i]).collect()
}

/// `mᵀ x` for a dense `m` (`n × k`) and `x` (`n` entries).
fn transpose_times(m: MatRef<'_, f64>, x: &[f64]) -> Vec<f64> {
    if m.ncols() == 0 {
        return Vec::new();
    }
    let x = Col::from_fn(x.len(), |i| x[i]);
    col_vec(&(m.transpose() * &x))
}
