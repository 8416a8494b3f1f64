//! Blocks of vectors packed in rows of [`WIDTH`] values (one 64-byte cache line per row): the
//! layout of the solver's hand-written loops (sparse products, Gram–Schmidt, triangular solves),
//! and the run-time choice of their AVX2 + FMA variants (the workspace is built for the
//! baseline x86-64 target, so each loop is compiled twice: portable and with AVX2 + FMA).

/// Values per packed row.
pub(crate) const WIDTH: usize = 8;

/// The values of up to [`WIDTH`] columns in one row (missing columns 0).
pub(crate) type Row = [f64; WIDTH];

/// Whether the loops compiled with AVX2 + FMA may run on this CPU.
pub(crate) fn has_avx2_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// `a + x · y`, fused when `FUSED` (only in functions compiled with FMA: elsewhere `mul_add`
/// would call a slow library routine).
#[inline(always)]
pub(crate) fn multiply_add<const FUSED: bool>(x: f64, y: f64, a: f64) -> f64 {
    if FUSED {
        x.mul_add(y, a)
    } else {
        a + x * y
    }
}
