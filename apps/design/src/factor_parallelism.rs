//! [`FactorParallelism`]: whether the full soft design's sparse factorization runs on one
//! thread or on all of them.

use crate::DesignError;
use faer::Par;

/// Below this many flops of one numeric factorization (`Σ_j c_j²`, see
/// [`crate::FullSoftDesign::factor_flop_count`]) [`FactorParallelism::Auto`] factors and solves
/// sequentially, unless the environment variable [`SEQUENTIAL_FLOP_LIMIT_VARIABLE`] gives
/// another limit (the crossover depends on the machine's cores and memory bandwidth).
///
/// Measured on the 2-core test machine (papers/`examples/full_soft_orderings.rs`, nested dissection,
/// whole first factorization, sequential vs faer's parallel, 2026-11-21): hand (4.5 Gflop)
/// 0.36 vs 0.40 s, rocker-arm (6.5 Gflop) 0.51 vs 0.64 s, bunny-closed (60 Gflop) 3.1 vs 4.5 s,
/// bumpy-torus-x4 (107 Gflop) 7.1 vs 5.7 s, armadillo-x4 (329 Gflop) 22.5 vs 20.9 s. Below
/// about 1e11 flops the supernodes are too small for faer's task synchronisation to pay off;
/// the limit sits between bunny-closed and bumpy-torus-x4.
pub const SEQUENTIAL_FLOP_LIMIT: f64 = 8.0e10;

/// Environment variable overriding [`SEQUENTIAL_FLOP_LIMIT`] (a number of flops, e.g. `1e11`).
pub const SEQUENTIAL_FLOP_LIMIT_VARIABLE: &str = "TVF_SEQUENTIAL_FLOP_LIMIT";

/// [`SEQUENTIAL_FLOP_LIMIT`], or the value of [`SEQUENTIAL_FLOP_LIMIT_VARIABLE`] when it is set.
///
/// Errors: [`DesignError::BadEnvironment`] if the variable is set but is not a non-negative
/// number (a typo would otherwise silently change which factorizations are threaded).
pub fn sequential_flop_limit() -> Result<f64, DesignError> {
    let Some(raw) = std::env::var_os(SEQUENTIAL_FLOP_LIMIT_VARIABLE) else {
        return Ok(SEQUENTIAL_FLOP_LIMIT);
    };
    let value = raw.to_string_lossy().into_owned();
    match value.trim().parse::<f64>() {
        Ok(limit) if limit >= 0.0 => Ok(limit),
        _ => Err(DesignError::BadEnvironment {
            variable: SEQUENTIAL_FLOP_LIMIT_VARIABLE,
            value,
            expected: "a non-negative number of flops, e.g. 1e11",
        }),
    }
}

/// How [`crate::FullSoftDesign`] parallelises its numeric factorizations and solves. faer's
/// global parallelism setting is never changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FactorParallelism {
    /// Sequential when the factorization needs fewer than [`sequential_flop_limit`] flops
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
    /// The faer parallelism for a factorization of `flops` flops, with `limit` the
    /// [`sequential_flop_limit`] (only [`FactorParallelism::Auto`] reads it).
    pub fn choose(self, flops: f64, limit: f64) -> Par {
        match self {
            FactorParallelism::Auto if flops < limit => Par::Seq,
            FactorParallelism::Auto => faer::get_global_parallelism(),
            FactorParallelism::Sequential => Par::Seq,
            FactorParallelism::Parallel => Par::rayon(0),
        }
    }
}
