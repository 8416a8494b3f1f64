//! [`ObservedBasisFile`]: a basis file read in blocks, shared, with an observer of its own — so
//! that each caller of one opened file (a Python call, say) is told the progress of its own
//! passes, whatever observer the blocks were opened with.

use super::basis_file_blocks::BasisFileBlocks;
use super::block_progress::BlockObserver;
use crate::{FieldBasis, FieldFamily, SpectralBasisError};
use std::sync::Arc;
use tvf_core::discretization::Mass;

/// `blocks`' products (bit for bit), each pass told to `observer` instead of the blocks' own.
pub struct ObservedBasisFile {
    blocks: Arc<BasisFileBlocks>,
    observer: Option<BlockObserver>,
}

impl ObservedBasisFile {
    /// `blocks` telling `observer` (`None`: nobody) the progress of every pass.
    pub fn new(blocks: Arc<BasisFileBlocks>, observer: Option<BlockObserver>) -> Self {
        Self { blocks, observer }
    }

    /// The blocks read.
    pub fn blocks(&self) -> &BasisFileBlocks {
        &self.blocks
    }
}

impl FieldBasis for ObservedBasisFile {
    fn len(&self) -> usize {
        self.blocks.len()
    }

    fn field_dimension(&self) -> usize {
        self.blocks.field_dimension()
    }

    fn eigenvalues(&self) -> &[f64] {
        self.blocks.eigenvalues()
    }

    fn families(&self) -> &[FieldFamily] {
        self.blocks.families()
    }

    fn coefficients(&self, field: &[f64]) -> Result<Vec<f64>, SpectralBasisError> {
        self.blocks
            .observed_coefficients(field, self.observer.as_ref())
    }

    fn reconstruct(&self, coefficients: &[f64]) -> Result<Vec<f64>, SpectralBasisError> {
        Ok(self.reconstruct_many(&[coefficients])?.remove(0))
    }

    fn reconstruct_many(&self, sets: &[&[f64]]) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        self.blocks
            .observed_reconstruct_many(sets, self.observer.as_ref())
    }

    fn inner_product(&self, a: &[f64], b: &[f64]) -> f64 {
        self.blocks.inner_product(a, b)
    }

    fn field_mass(&self) -> &Mass {
        self.blocks.field_mass()
    }

    fn rows(&self, rows: &[usize]) -> Result<Vec<Vec<f64>>, SpectralBasisError> {
        self.blocks.observed_rows(rows, self.observer.as_ref())
    }

    fn visit_fields(
        &self,
        visit: &(dyn Fn(usize, &[f64]) + Sync),
    ) -> Result<(), SpectralBasisError> {
        self.blocks
            .observed_visit_fields(visit, self.observer.as_ref())
    }
}
