//! The one run-time choice between the two compilations of the solver's hand-written loops
//! (Gram–Schmidt, packing, triangular solves, eigenfield residuals): a loop is written once,
//! generic over a flag `FUSED` that fuses its multiply–adds ([`multiply_add`]), and
//! [`fma_dispatch!`] runs it with `FUSED` inside a function compiled for AVX2 + FMA where the
//! CPU has them, portable otherwise (the workspace is built for the baseline x86-64 target).
//! The two compilations differ in rounding only.
//!
//! The compiled function takes the loop's arguments as its own parameters, so the compiler
//! still knows that a `&mut` slice aliases nothing else; handing the loop over as one value (a
//! closure, or a struct of its arguments) hides that, and the packed triangular solves took
//! 3 % more instructions that way (`callgrind` of the `eigen_fingerprint` example).
//!
//! Why not pulp (faer's SIMD layer, already in the build): its `Arch::dispatch` hands a loop a
//! generic SIMD type to be written in, whereas these loops are scalar code over packed rows of
//! eight values that the compiler vectorises (two use intrinsics), so only the detection and
//! the compiled wrapper would move to it; its wrapper takes the loop as one value (see above),
//! and its token asks for the whole x86-64-v3 level (BMI1/2, LZCNT, ...) rather than the two
//! features the loops use.

/// Whether the loops compiled with AVX2 + FMA may run on this CPU (detected once per process
/// by the standard library).
#[inline]
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

/// Runs a hand-written loop in its best compilation for this CPU.
///
/// - `fma_dispatch!(body(a: A, b: B) -> R)`: `body::<true>(a, b)` inside a function compiled
///   for AVX2 + FMA where the CPU has them, else `body::<false>(a, b)`. `body` is generic over
///   `const FUSED: bool` and `#[inline(always)]` (so that it is compiled into that function).
/// - `fma_dispatch!(fused(a, b) else portable(a, b))`: `fused`, a function compiled for AVX2 +
///   FMA itself (a loop written with intrinsics), where the CPU has them, else the expression
///   `portable(a, b)`.
macro_rules! fma_dispatch {
    ($body:ident($($arg:ident: $ty:ty),* $(,)?) $(-> $ret:ty)?) => {{
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2,fma")]
        fn fused($($arg: $ty),*) $(-> $ret)? {
            $body::<true>($($arg),*)
        }
        match () {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the CPU has the features `fused` is compiled for.
            () if $crate::kernel_dispatch::has_avx2_fma() => unsafe { fused($($arg),*) },
            () => $body::<false>($($arg),*),
        }
    }};
    ($fused:ident($($arg:expr),* $(,)?) else $portable:expr) => {
        match () {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the CPU has the features the function is compiled for.
            () if $crate::kernel_dispatch::has_avx2_fma() => unsafe { $fused($($arg),*) },
            () => $portable,
        }
    };
}
pub(crate) use fma_dispatch;

/// `a + x · y`, fused when `FUSED` (only in a loop compiled with FMA, see [`fma_dispatch!`]:
/// elsewhere `mul_add` would call a slow library routine).
#[inline(always)]
pub(crate) fn multiply_add<const FUSED: bool>(x: f64, y: f64, a: f64) -> f64 {
    if FUSED {
        x.mul_add(y, a)
    } else {
        a + x * y
    }
}
