//! The one run-time choice between the two compilations of the solver's hand-written loops
//! (Gram–Schmidt, packing, triangular solves, eigenfield residuals): each loop is written once
//! as a [`Kernel`], generic over a flag `FUSED` that fuses its multiply–adds
//! ([`multiply_add`]), and [`run`] calls it with `FUSED` inside a function compiled for AVX2 +
//! FMA where the CPU has them, portable otherwise (the workspace is built for the baseline
//! x86-64 target). The two compilations differ in rounding only.
//!
//! Why not pulp (faer's SIMD layer, already in the build): its `Arch::dispatch` hands a loop a
//! generic SIMD type to be written in, whereas these loops are scalar code over packed rows of
//! eight values that the compiler vectorises (two use intrinsics), so only the detection and
//! the wrapper function below would move to it, and its token asks for the whole x86-64-v3
//! level (BMI1/2, LZCNT, ...) rather than the two features the loops use.

/// A hand-written loop with its arguments, compiled once per value of `FUSED`.
///
/// An implementation marks [`Kernel::run`] `#[inline(always)]`: that is what compiles its body
/// inside [`run`]'s AVX2 + FMA function.
pub(crate) trait Kernel {
    /// What the loop returns.
    type Output;

    /// Runs the loop, multiply–adds fused when `FUSED`.
    ///
    /// # Safety
    ///
    /// `FUSED` only where the CPU has AVX2 and FMA (as [`run`] makes sure): the loop may call
    /// functions compiled for them.
    unsafe fn run<const FUSED: bool>(self) -> Self::Output;
}

/// Runs `kernel`: fused, in a function compiled for AVX2 + FMA, where the CPU has them
/// (detected once per process by the standard library); portable otherwise.
#[inline(always)]
pub(crate) fn run<K: Kernel>(kernel: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
        // SAFETY: the CPU has the features `run_fused` is compiled for, which are the ones
        // `Kernel::run::<true>` may assume.
        return unsafe { run_fused(kernel) };
    }
    // SAFETY: `FUSED` is false.
    unsafe { kernel.run::<false>() }
}

/// `kernel` with `FUSED`, its body inlined here and so compiled with AVX2 + FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn run_fused<K: Kernel>(kernel: K) -> K::Output {
    // SAFETY: a function compiled for AVX2 + FMA runs only where the CPU has them.
    unsafe { kernel.run::<true>() }
}

/// `a + x · y`, fused when `FUSED` (only in a [`Kernel`] run with FMA: elsewhere `mul_add`
/// would call a slow library routine).
#[inline(always)]
pub(crate) fn multiply_add<const FUSED: bool>(x: f64, y: f64, a: f64) -> f64 {
    if FUSED {
        x.mul_add(y, a)
    } else {
        a + x * y
    }
}
