//! Large work matrices on transparent huge pages.
//!
//! Why: the eigensolver's biggest matrices (the slices' Krylov bases and locked vectors, the
//! eigenvectors: hundreds of MB on the bunny, GBs at a million faces) are fresh allocations that
//! the kernel backs page by page on first touch, one fault per 4 KiB page.
//! Advised for huge pages (`madvise(MADV_HUGEPAGE)`, honoured when
//! `/sys/kernel/mm/transparent_hugepage/enabled` is `always` or `madvise`, the common default),
//! such a matrix faults once per 2 MiB instead of once per 4 KiB page, which cuts the page
//! faults and some system time (numbers in `docs/performance.md`). The kernel still zeroes
//! every fresh page, which remains most of that system time. Where the advice is not available (other systems, THP
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
    let bytes = matrix.col_stride().unsigned_abs() * columns * std::mem::size_of::<f64>();
    advise_huge_pages(matrix.as_ptr() as usize, bytes);
    matrix
}

/// An empty vector with room for `len` values, advised like [`reserve_on_huge_pages`].
pub(crate) fn reserve_values_on_huge_pages(len: usize) -> Vec<f64> {
    let values = Vec::<f64>::with_capacity(len);
    advise_huge_pages(values.as_ptr() as usize, len * std::mem::size_of::<f64>());
    values
}

/// Advises the whole huge pages inside `[start, start + bytes)`, untouched memory of a fresh
/// allocation, for transparent huge pages.
fn advise_huge_pages(start: usize, bytes: usize) {
    #[cfg(target_os = "linux")]
    {
        let (first, end) = (
            start.next_multiple_of(HUGE_PAGE),
            (start + bytes) / HUGE_PAGE * HUGE_PAGE,
        );
        if end > first {
            // SAFETY: [first, end) lies inside a fresh allocation that the caller owns and has
            // not touched; the advice changes how the kernel backs those pages, not their
            // contents or validity. Failure (e.g. THP compiled out) only means no advice.
            unsafe {
                libc::madvise(first as *mut libc::c_void, end - first, libc::MADV_HUGEPAGE);
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (start, bytes);
}

/// Size of the smallest page the kernel releases.
#[cfg(target_os = "linux")]
const PAGE: usize = 4096;

/// Gives the whole pages inside `[start, start + bytes)` back to the kernel
/// (`madvise(MADV_DONTNEED)`): the memory stays reserved, reads as zeros from then on, and no
/// longer counts as resident. A no-op elsewhere than Linux.
///
/// # Safety
/// `[start, start + bytes)` lies inside an allocation the caller owns, and nothing reads its
/// contents again (nor writes them while this runs).
pub(crate) unsafe fn release_pages(start: usize, bytes: usize) {
    #[cfg(target_os = "linux")]
    {
        let (first, end) = (start.next_multiple_of(PAGE), (start + bytes) / PAGE * PAGE);
        if end > first {
            // Failure only means the pages stay resident.
            libc::madvise(first as *mut libc::c_void, end - first, libc::MADV_DONTNEED);
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (start, bytes);
}
