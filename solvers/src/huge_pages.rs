//! Large work matrices on transparent huge pages.
//!
//! Why: the eigensolver's biggest matrices (each interval's Krylov basis, its locked vectors,
//! the assembled eigenvectors: hundreds of MB on the bunny, GBs at a million faces) are fresh
//! allocations that the kernel backs page by page on first touch. In 4 KiB pages that costs one
//! fault per page: about 2 GB/s of first-touch bandwidth on the 2-core test VM, and 10 % of a
//! bunny-closed basis computation's processor time in the kernel. Advised for huge pages
//! (`madvise(MADV_HUGEPAGE)`, honoured when `/sys/kernel/mm/transparent_hugepage/enabled` is
//! `always` or `madvise`, the common default), such a matrix faults once per 2 MiB, and the
//! sweeps over it miss the TLB less. Where the advice is not available (other systems, THP
//! disabled) it is a no-op and the matrix is an ordinary one.

use faer::Mat;

/// Size of a transparent huge page on x86-64 and most Linux configurations.
#[cfg(target_os = "linux")]
const HUGE_PAGE: usize = 2 << 20;

/// An empty `f64` matrix with room for `rows × columns` values, whose untouched memory is
/// advised for transparent huge pages (see the module documentation): grow it with
/// `resize_with`, which is when the memory is first touched.
pub(crate) fn reserve_on_huge_pages(rows: usize, columns: usize) -> Mat<f64> {
    let matrix = Mat::<f64>::with_capacity(rows, columns);
    #[cfg(target_os = "linux")]
    {
        let bytes = matrix.col_stride().unsigned_abs() * columns * std::mem::size_of::<f64>();
        let start = matrix.as_ptr() as usize;
        let (first, end) = (
            start.next_multiple_of(HUGE_PAGE),
            (start + bytes) / HUGE_PAGE * HUGE_PAGE,
        );
        if end > first {
            // SAFETY: [first, end) lies inside the matrix's own allocation, which is untouched
            // and owned by it; the advice changes how the kernel backs those pages, not their
            // contents or validity. Failure (e.g. THP compiled out) only means no advice.
            unsafe {
                libc::madvise(first as *mut libc::c_void, end - first, libc::MADV_HUGEPAGE);
            }
        }
    }
    matrix
}

/// A `rows × columns` zero matrix on transparent huge pages ([`reserve_on_huge_pages`]).
pub(crate) fn zeros_on_huge_pages(rows: usize, columns: usize) -> Mat<f64> {
    let mut matrix = reserve_on_huge_pages(rows, columns);
    matrix.resize_with(rows, columns, |_, _| 0.0);
    matrix
}
