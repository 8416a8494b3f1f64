//! [`FactorParallelism`]: whether the full soft design's sparse factorization runs on one
//! thread or on all of them.

use faer::Par;

/// Below this many flops of one numeric factorization (`Σ_j c_j²`, see
/// [`crate::FullSoftDesign::factor_flop_count`]) [`FactorParallelism::Auto`] factors and solves
/// sequentially.
///
/// Measured on the 2-core test machine (`examples/full_soft_orderings.rs`, nested dissection;
/// numeric factorization, sequential vs faer's parallel): see `SEQUENTIAL_FLOP_LIMIT` in the
/// session note of issue 7. Small factors (hand: 4.5 Gflop, rocker-arm: 6.5 Gflop) have many
/// small supernodes, where faer's task synchronisation costs more than the second core gains.
pub const SEQUENTIAL_FLOP_LIMIT: f64 = 2.0e10;

/// How [`crate::FullSoftDesign`] parallelises its numeric factorizations and solves. faer's
/// global parallelism setting is never changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FactorParallelism {
    /// Sequential when the factorization needs fewer than [`SEQUENTIAL_FLOP_LIMIT`] flops
    /// (decided after the symbolic analysis, before any numeric work), otherwise faer's global
    /// parallelism.
    #[default]
    Auto,
    /// Always one thread.
    Sequential,
    /// Always all threads (rayon's pool), whatever faer's global setting.
    Parallel,
}

impl FactorParallelism {
    /// The faer parallelism for a factorization of `flops` flops.
    pub fn choose(self, flops: f64) -> Par {
        match self {
            FactorParallelism::Auto if flops < SEQUENTIAL_FLOP_LIMIT => Par::Seq,
            FactorParallelism::Auto => faer::get_global_parallelism(),
            FactorParallelism::Sequential => Par::Seq,
            FactorParallelism::Parallel => Par::rayon(0),
        }
    }
}
