//! Work memory handed from one eigensolver job to the next.
//!
//! Why: each Krylov–Schur slice needs a basis of `n × (2·wanted + 7·block)` values (190 MB for
//! the Crouzeix–Raviart bunny-closed pencil, 2.7 GB at a million faces). Allocated fresh per
//! slice, every page of it is faulted in and zeroed by the kernel on first touch, which made the
//! Krylov bases a large share of the process's kernel time (see `docs/performance.md`).
//! Recycled, a slice starts on memory that is already mapped.
//!
//! A returned workspace is kept only while some job has not yet started: the pool never holds
//! memory that no later job will use (at a million faces one spare basis costs GBs, and the
//! last jobs' refinement and the assembly of the eigenvectors follow).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Spare workspaces of type `T` for a known number of jobs.
pub(crate) struct WorkspacePool<T> {
    spare: Mutex<Vec<T>>,
    unstarted: AtomicUsize,
}

impl<T: Default> WorkspacePool<T> {
    /// A pool for `jobs` jobs, each of which calls [`Self::take`] once (more calls are allowed,
    /// they just find nothing once the count is used up).
    pub(crate) fn new(jobs: usize) -> Self {
        Self {
            spare: Mutex::new(Vec::new()),
            unstarted: AtomicUsize::new(jobs),
        }
    }

    /// A spare workspace, or a new empty one (`T::default()`); counts one job as started.
    pub(crate) fn take(&self) -> T {
        // Saturating: a split interval runs more slices than were counted.
        let _ = self
            .unstarted
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |left| {
                left.checked_sub(1)
            });
        self.lock().pop().unwrap_or_default()
    }

    /// Returns a workspace: kept for a later job, or dropped if every job has started.
    pub(crate) fn give_back(&self, workspace: T) {
        if self.unstarted.load(Ordering::Relaxed) > 0 {
            self.lock().push(workspace);
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<T>> {
        // A poisoned pool (a panic in another job) holds nothing that could be wrong: spare
        // memory whose contents are never relied on.
        self.spare
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A returned workspace is reused while jobs remain, and dropped once all have started.
    #[test]
    fn keeps_workspaces_only_for_jobs_not_yet_started() {
        let pool = WorkspacePool::<Vec<u8>>::new(2);
        let mut first = pool.take();
        first.extend_from_slice(b"spare");
        pool.give_back(first);
        let second = pool.take();
        assert_eq!(
            second, b"spare",
            "the second job reuses the first job's memory"
        );
        pool.give_back(second);
        assert!(
            pool.take().is_empty(),
            "nothing is kept once every job started"
        );
    }
}
