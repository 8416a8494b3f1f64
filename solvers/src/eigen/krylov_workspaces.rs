//! [`KrylovWorkspaces`]: the Krylov basis buffers of finished slices, kept for the next slice.
//!
//! A slice's basis is `n × (max_basis + 3·block)` numbers (183 MB for the Crouzeix–Raviart
//! pencil of a 70k-face mesh). Allocated afresh for every interval, each one is zeroed and then
//! faulted in page by page by the kernel, and handed back to it at the end: on bunny-closed those
//! page faults were the largest part of the system time of a whole basis computation. The
//! buffers of one eigensolver call are kept here instead and reused.

use faer::Mat;
use std::sync::Mutex;

/// Basis buffers returned by finished slices, ready for the next ones.
#[derive(Default)]
pub(crate) struct KrylovWorkspaces {
    free: Mutex<Vec<Mat<f64>>>,
}

impl KrylovWorkspaces {
    /// A buffer of `rows` rows and at least `columns` columns, contents unspecified: a kept one
    /// if one fits, else a new one. Kept buffers with another number of rows are freed on the
    /// way: the jobs run largest dimension first, so a pencil's buffers are not asked for again
    /// once a smaller pencil's jobs have started.
    pub(crate) fn take(&self, rows: usize, columns: usize) -> Mat<f64> {
        let kept = {
            let mut free = self.free.lock().unwrap_or_else(|e| e.into_inner());
            free.retain(|buffer| buffer.nrows() == rows);
            free.iter()
                .position(|buffer| buffer.ncols() >= columns)
                .map(|at| free.swap_remove(at))
        };
        kept.unwrap_or_else(|| Mat::zeros(rows, columns))
    }

    /// Keeps `buffer` for a later [`take`](Self::take).
    pub(crate) fn give_back(&self, buffer: Mat<f64>) {
        self.free
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(buffer);
    }
}
