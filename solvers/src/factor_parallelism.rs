//! [`FactorParallelism`]: whether a sparse factorization (and the solves with it) runs on one
//! thread or on all of them, chosen from its flop count after the symbolic analysis.

use faer::Par;

/// Below this many flops of one numeric factorization (`Σ_j c_j²` over the columns of `L`)
/// [`FactorParallelism::default`] factors and solves sequentially (the crossover depends on the
/// machine's cores and memory bandwidth; binaries may let users override it).
///
/// Below about 1e11 flops the supernodes are too small for faer's task synchronisation to pay
/// off: the full soft designs of the Table 1 meshes factored faster sequentially up to
/// bunny-closed (60 Gflop) and faster in parallel from bumpy-torus-x4 (107 Gflop) on, and the
/// limit sits between them (timings and the command in `docs/performance.md`).
pub const SEQUENTIAL_FLOP_LIMIT: f64 = 8.0e10;

/// How a factorization and its solves are threaded. faer's global parallelism setting is never
/// changed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FactorParallelism {
    /// Sequential when the factorization needs fewer than `sequential_flop_limit` flops
    /// (decided after the symbolic analysis, before any numeric work), otherwise faer's global
    /// parallelism.
    Auto {
        /// Flops below which one thread is used (default [`SEQUENTIAL_FLOP_LIMIT`]).
        sequential_flop_limit: f64,
    },
    /// Always one thread.
    Sequential,
    /// Always all threads (rayon's pool), whatever faer's global setting.
    Parallel,
}

impl Default for FactorParallelism {
    fn default() -> Self {
        FactorParallelism::Auto {
            sequential_flop_limit: SEQUENTIAL_FLOP_LIMIT,
        }
    }
}

impl FactorParallelism {
    /// The faer parallelism for a factorization of `flops` flops.
    pub fn choose(self, flops: f64) -> Par {
        match self {
            FactorParallelism::Auto {
                sequential_flop_limit,
            } if flops < sequential_flop_limit => Par::Seq,
            FactorParallelism::Auto { .. } => faer::get_global_parallelism(),
            FactorParallelism::Sequential => Par::Seq,
            FactorParallelism::Parallel => Par::rayon(0),
        }
    }
}
