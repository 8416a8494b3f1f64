//! The discrete Hodge decomposition `v = d0 f − M1⁻¹ d1ᵀ g + h` of a field, for any
//! [`HodgeComplex`], and a basis of the harmonic fields.

use crate::mixed_poisson::MixedPoisson;
use crate::pinned_poisson::PinnedPoisson;
use crate::DecompositionError;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::sparse::{mul_transpose_vec, mul_vec};
use tvf_core::discretization::{DiscretizationError, HodgeComplex, HodgeOperators};

/// The three `M1`-orthogonal parts of a field and their potentials.
#[derive(Debug, Clone, PartialEq)]
pub struct HodgeParts {
    /// Potential `f` (`n0` pointwise values, zero mean per component with constants in the kernel,
    /// zero on Dirichlet nodes): `integrable = d0 f`.
    pub potential: Vec<f64>,
    /// Co-potential `g` (`n2` pointwise values, normalised like the potential):
    /// `cointegrable = −M1⁻¹ d1ᵀ g` (finite elements: `J G_co g`).
    pub co_potential: Vec<f64>,
    /// Integrable (curl-free) part `d0 f` (`n1`).
    pub integrable: Vec<f64>,
    /// Co-integrable (divergence-free) part `−M1⁻¹ d1ᵀ g` (`n1`).
    pub cointegrable: Vec<f64>,
    /// Harmonic part `h = v − d0 f + M1⁻¹ d1ᵀ g` (`n1`): in the kernel of the Hodge–Laplacian.
    pub harmonic: Vec<f64>,
}

/// Prefactored Hodge decomposition of one complex: both singular Poisson systems
/// `(d0ᵀ M1 d0) f = d0ᵀ M1 v` and `(d1 M1⁻¹ d1ᵀ) g = −d1 v` are factored once (one node pinned per
/// connected component whose constants are in the kernel, every Dirichlet node fixed to zero), so
/// decomposing many fields costs two triangular solves each. Where `M1` is not diagonal, the
/// co-exact system is dense and is solved in mixed form (`MixedPoisson`: a sparse saddle
/// system and a few refinement steps).
#[derive(Debug)]
pub struct HodgeDecomposer<'a, H: HodgeComplex + ?Sized> {
    complex: &'a H,
    exact: PinnedPoisson,
    co_exact: CoExactPoisson,
}

/// The co-exact Poisson solve: a sparse stiffness, or the mixed form of a dense one.
// One per decomposer, built once: the size of the larger variant costs nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Debug)]
enum CoExactPoisson {
    Pinned(PinnedPoisson),
    Mixed(MixedPoisson),
}

impl CoExactPoisson {
    fn solve_many(&self, rhs: &[&[f64]]) -> Vec<Vec<f64>> {
        match self {
            CoExactPoisson::Pinned(p) => p.solve_many(rhs),
            CoExactPoisson::Mixed(p) => p.solve_many(rhs),
        }
    }
}

impl<'a, H: HodgeComplex + ?Sized> HodgeDecomposer<'a, H> {
    /// Factors the two Poisson systems of `complex` (on a mesh with boundary, on the free nodes
    /// of each space: the boundary condition is in the complex). Fails if a factorization fails.
    pub fn new(complex: &'a H) -> Result<Self, DecompositionError> {
        let exact = PinnedPoisson::new(
            complex.potential_stiffness(),
            complex.potential_nodes(),
            complex.m0(),
        )?;
        let co_potential_mass = complex.m2().inverse();
        let co_exact = match complex.co_potential_stiffness().as_sparse() {
            Some(stiffness) => CoExactPoisson::Pinned(PinnedPoisson::new(
                stiffness,
                complex.co_potential_nodes(),
                &co_potential_mass,
            )?),
            None => CoExactPoisson::Mixed(MixedPoisson::new(
                complex.m1(),
                complex.d1(),
                &co_potential_mass,
                complex.field_nodes(),
                complex.co_potential_nodes(),
            )?),
        };
        Ok(Self {
            complex,
            exact,
            co_exact,
        })
    }

    /// The complex this decomposer belongs to.
    pub fn complex(&self) -> &'a H {
        self.complex
    }

    /// Decomposes `field` (`n1` coefficients) into its integrable, co-integrable and harmonic
    /// parts, per connected component. Fails on a wrong length, a non-finite value, or a nonzero
    /// value at a Dirichlet field node (relative forms: a boundary edge).
    pub fn decompose(&self, field: &[f64]) -> Result<HodgeParts, DecompositionError> {
        let mut parts = self.decompose_many(&[field])?;
        Ok(parts.pop().expect("one field, one decomposition"))
    }

    /// [`Self::decompose`] for several fields at once: each Poisson system is solved for all of
    /// them as one multi-column block (its factor read once per block, not once per field), so
    /// `k` fields cost much less than `k` decompositions. The parts are those of each field
    /// decomposed alone up to round-off (the block solves sum in another order); one field gives
    /// the same bits as [`Self::decompose`]. Fails as `decompose` does on the first bad field.
    pub fn decompose_many(&self, fields: &[&[f64]]) -> Result<Vec<HodgeParts>, DecompositionError> {
        let c = self.complex;
        for field in fields {
            self.check_field(field)?;
        }
        let divergences: Vec<Vec<f64>> = fields
            .iter()
            .map(|field| mul_transpose_vec(c.d0(), &c.m1().apply(field)))
            .collect();
        let curls: Vec<Vec<f64>> = fields
            .iter()
            .map(|field| mul_vec(c.d1(), field).iter().map(|x| -x).collect())
            .collect();
        let potentials = self.exact.solve_many(&as_slices(&divergences));
        let co_potentials = self.co_exact.solve_many(&as_slices(&curls));
        let parts = fields
            .iter()
            .zip(potentials)
            .zip(co_potentials)
            .map(|((field, potential), co_potential)| {
                let integrable = c.gradient_field(&potential);
                let cointegrable = c.co_gradient_field(&co_potential);
                let harmonic = field
                    .iter()
                    .zip(&integrable)
                    .zip(&cointegrable)
                    .map(|((v, a), b)| v - a - b)
                    .collect();
                HodgeParts {
                    potential,
                    co_potential,
                    integrable,
                    cointegrable,
                    harmonic,
                }
            })
            .collect();
        Ok(parts)
    }

    /// A field can be decomposed: `n1` finite coefficients, zero on the Dirichlet field nodes.
    fn check_field(&self, field: &[f64]) -> Result<(), DecompositionError> {
        let c = self.complex;
        let dimension = c.field_dimension();
        if field.len() != dimension {
            return Err(DiscretizationError::DimensionMismatch {
                what: "field to decompose",
                expected: dimension,
                found: field.len(),
            }
            .into());
        }
        if let Some(index) = field.iter().position(|x| !x.is_finite()) {
            return Err(DiscretizationError::NonFinite {
                what: "field to decompose",
                index,
            }
            .into());
        }
        let fixed = &c.field_nodes().dirichlet;
        if let Some(index) = (0..dimension).find(|&i| fixed[i] && field[i] != 0.0) {
            return Err(DiscretizationError::NonzeroOnDirichletNode {
                what: "field to decompose",
                index,
                value: field[index],
            }
            .into());
        }
        Ok(())
    }

    /// The harmonic part of `field` alone.
    pub fn harmonic_part(&self, field: &[f64]) -> Result<Vec<f64>, DecompositionError> {
        Ok(self.decompose(field)?.harmonic)
    }

    /// The harmonic parts of several fields, through [`Self::decompose_many`].
    pub fn harmonic_parts(&self, fields: &[&[f64]]) -> Result<Vec<Vec<f64>>, DecompositionError> {
        Ok(self
            .decompose_many(fields)?
            .into_iter()
            .map(|parts| parts.harmonic)
            .collect())
    }

    /// An `M1`-orthonormal basis of the harmonic fields (`harmonic_dimension()` fields of length
    /// `n1`): random fields (seeded, zero on the Dirichlet field nodes) projected onto `H`, then
    /// two passes of Gram–Schmidt in `M1` against the fields before, each followed by a
    /// re-projection onto `H` for accuracy (`docs/conventions.md`): three decompositions a field.
    pub fn harmonic_basis(&self, seed: u64) -> Result<Vec<Vec<f64>>, DecompositionError> {
        let c = self.complex;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let harmonic_dimension = c.topology().harmonic_dimension;
        let mut basis: Vec<Vec<f64>> = Vec::with_capacity(harmonic_dimension);
        let nodes = c.field_nodes();
        for _ in 0..harmonic_dimension {
            let random: Vec<f64> = (0..c.field_dimension())
                .map(|i| {
                    let x = rng.random_range(-1.0..1.0);
                    if nodes.dirichlet[i] {
                        0.0
                    } else {
                        x
                    }
                })
                .collect();
            let mut h = self.harmonic_part(&random)?;
            for _pass in 0..2 {
                for b in &basis {
                    let coefficient = c.field_inner(&h, b);
                    h.iter_mut().zip(b).for_each(|(x, y)| *x -= coefficient * y);
                }
                h = self.harmonic_part(&h)?;
            }
            let norm = c.field_inner(&h, &h).sqrt();
            h.iter_mut().for_each(|x| *x /= norm);
            basis.push(h);
        }
        Ok(basis)
    }
}

/// Borrowed views of owned vectors.
fn as_slices(vectors: &[Vec<f64>]) -> Vec<&[f64]> {
    vectors.iter().map(Vec::as_slice).collect()
}
