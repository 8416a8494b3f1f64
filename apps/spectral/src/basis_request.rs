//! [`BasisRequest`]: which eigenfields [`crate::compute_basis`] computes, with which seed, and
//! whom it tells about its progress.

use std::fmt;

/// How many eigenfields to compute. Harmonic fields (eigenvalue 0, `2g` of them) are always
/// included first, except by [`BasisSize::Fields`] with fewer fields than `2g`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BasisSize {
    /// The `d` eigenfields of lowest eigenvalue of the Hodge–Laplacian `L` (harmonic ones
    /// included), whichever family they belong to.
    Fields(usize),
    /// All harmonic fields plus the lowest `k` integrable and the lowest `k` co-integrable
    /// eigenfields (the paper's "k pairs", e.g. 500 + 500). Fewer if a family has fewer.
    Pairs(usize),
    /// Every eigenfield with eigenvalue `λ ≤ bound` (units 1/length², `bound ≥ 0`); the frequency
    /// bound `ω` corresponds to `λ = ω²`.
    MaxEigenvalue(f64),
    /// The complete basis of `X_h` (`n1` fields on a closed mesh), by dense eigensolvers: for
    /// small meshes only (a few thousand nodes).
    Complete,
}

/// The stage a basis computation is in, reported through [`BasisRequest::progress`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BasisStage {
    /// Projecting random fields onto the harmonic space.
    Harmonic,
    /// Eigenpairs of both Laplacians (potential and co-potential), computed at the same time;
    /// `done` and `wanted` count both families.
    Eigenpairs,
    /// Turning eigenfunctions into fields and sorting them.
    Assembling,
}

impl BasisStage {
    /// Lower-case name for messages.
    pub fn name(self) -> &'static str {
        match self {
            BasisStage::Harmonic => "harmonic fields",
            BasisStage::Eigenpairs => "eigenfields of both families",
            BasisStage::Assembling => "assembling",
        }
    }
}

/// A progress report of [`crate::compute_basis`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BasisProgress {
    /// What is being computed.
    pub stage: BasisStage,
    /// Items of this stage done so far (fields or eigenpairs).
    pub done: usize,
    /// Items this stage is after.
    pub wanted: usize,
}

/// What [`crate::compute_basis`] should compute.
#[derive(Clone, Copy)]
pub struct BasisRequest<'a> {
    /// How many fields.
    pub size: BasisSize,
    /// Seed of the random fields (harmonic projection) and of the eigensolver's start blocks:
    /// equal seeds give bit-identical bases.
    pub seed: u64,
    /// Keep the eigenfunctions next to the dense fields in the returned
    /// [`crate::SpectralBasis`] (see [`crate::SpectralBasis::eigenfunctions`]). Default `false`.
    pub keep_eigenfunctions: bool,
    /// Also store an `f32` copy of the fields for fast reconstruction
    /// ([`crate::SpectralBasis::reconstruct_f32`]). Default `false`.
    pub single_precision_copy: bool,
    /// Called with a report whenever a stage makes progress; `None` for silence.
    pub progress: Option<&'a dyn Fn(&BasisProgress)>,
}

impl<'a> BasisRequest<'a> {
    /// A request of the given size with seed 0 and no progress callback.
    pub fn new(size: BasisSize) -> Self {
        Self {
            size,
            seed: 0,
            keep_eigenfunctions: false,
            single_precision_copy: false,
            progress: None,
        }
    }

    /// The `d` lowest eigenfields of `L` ([`BasisSize::Fields`]).
    pub fn fields(count: usize) -> Self {
        Self::new(BasisSize::Fields(count))
    }

    /// The `count` lowest eigenfields of a complex with `field_dimension` (`n1`) field
    /// coefficients: [`BasisRequest::fields`], or the complete basis
    /// ([`BasisRequest::complete`]) when `count ≥ n1` (there are no more).
    pub fn lowest(count: usize, field_dimension: usize) -> Self {
        if count >= field_dimension {
            Self::complete()
        } else {
            Self::fields(count)
        }
    }

    /// Harmonic fields plus `k` integrable and `k` co-integrable eigenfields ([`BasisSize::Pairs`]).
    pub fn pairs(k: usize) -> Self {
        Self::new(BasisSize::Pairs(k))
    }

    /// Every eigenfield with eigenvalue at most `bound` ([`BasisSize::MaxEigenvalue`]).
    pub fn max_eigenvalue(bound: f64) -> Self {
        Self::new(BasisSize::MaxEigenvalue(bound))
    }

    /// Every eigenfield with frequency `√λ` at most `frequency`.
    pub fn max_frequency(frequency: f64) -> Self {
        Self::new(BasisSize::MaxEigenvalue(frequency * frequency))
    }

    /// The complete basis ([`BasisSize::Complete`], small meshes only).
    pub fn complete() -> Self {
        Self::new(BasisSize::Complete)
    }

    /// The same request with another seed.
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// The same request with a progress callback.
    pub fn with_progress(mut self, progress: &'a dyn Fn(&BasisProgress)) -> Self {
        self.progress = Some(progress);
        self
    }

    /// The same request, keeping the eigenfunctions in the result.
    pub fn keeping_eigenfunctions(mut self) -> Self {
        self.keep_eigenfunctions = true;
        self
    }

    /// The same request, with an `f32` copy of the fields in the result.
    pub fn with_single_precision_copy(mut self) -> Self {
        self.single_precision_copy = true;
        self
    }

    pub(crate) fn report(&self, stage: BasisStage, done: usize, wanted: usize) {
        if let Some(callback) = self.progress {
            callback(&BasisProgress {
                stage,
                done,
                wanted,
            });
        }
    }
}

impl fmt::Debug for BasisRequest<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("BasisRequest")
            .field("size", &self.size)
            .field("seed", &self.seed)
            .field("keep_eigenfunctions", &self.keep_eigenfunctions)
            .field("single_precision_copy", &self.single_precision_copy)
            .field("progress", &self.progress.map(|_| "callback"))
            .finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lowest_fields_of_all_or_more_are_the_complete_basis() {
        assert_eq!(BasisRequest::lowest(5, 40).size, BasisSize::Fields(5));
        assert_eq!(BasisRequest::lowest(40, 40).size, BasisSize::Complete);
        assert_eq!(BasisRequest::lowest(400, 40).size, BasisSize::Complete);
    }
}
