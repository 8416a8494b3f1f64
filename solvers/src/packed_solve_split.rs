//! The split of a supernodal factor's packed triangular solves between two threads.
//!
//! Why: the Krylov slices solve with one factorization at a time on one thread, which is the
//! right use of two cores when two slices run at once, but at a million faces the slice memory
//! budget runs one co-potential slice alone, and its solves (a fifth of its processor time,
//! measured with `perf`) left the second core idle. faer's parallel supernodal solve works a
//! column at a time through its general kernels (see `packed_ldlt_solve.rs`), so the split is
//! made here, on the elimination tree.
//!
//! The supernodes are cut into three ranges: a first part `0..m`, a second part `m..t` and the
//! top `t..N`, such that no supernode of the first part updates (has a pattern row in) the
//! second; the top holds every row either part reaches beyond itself. Then the forward pass
//! runs the two parts at once, each on its own rows, keeping the values it would have
//! subtracted from top rows; those updates are made afterwards, the first part's before the
//! second's, then the top's own forward pass: every row sees the same operations in the same
//! order as on one thread, so the solution is the same bit for bit. The backward pass runs
//! the top first, then the two parts at once (each reads the top and writes only its own
//! rows).
//!
//! `m` and `t` minimise the work on the critical path, `max(w(first), w(second)) + w(top)`, with
//! `w` the stored entries plus rows of a range's supernodes; for each `m` the largest valid `t`
//! is the least parent of a first-part supernode at or above `m` (a supernode's pattern rows
//! lie in its ancestors, which the check of every first-part pattern confirms).

use crate::packed_ldlt_solve::KeptValues;
use crate::packed_rows::{Row, WIDTH};
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::ops::Range;

/// The `base` of a supernode whose pattern reaches no top row (see [`KeptValues`]).
pub(crate) const NOT_KEPT: usize = usize::MAX;

/// A split is made only where it takes at least this share of the work off the critical path.
const MIN_SAVING: f64 = 0.2;

/// Factors with fewer stored entries and rows are solved on one thread (the split would not
/// repay its bookkeeping).
const MIN_WORK: usize = 1 << 16;

/// The split of one symbolic factor (see the module documentation).
#[derive(Debug, Clone)]
pub(crate) struct SolveSplit {
    /// First supernode of the second part (`m`).
    second: usize,
    /// First supernode of the top (`t`).
    top: usize,
    /// Number of supernodes (`N`).
    supernodes: usize,
    /// First unknown of the second part.
    second_unknown: usize,
    /// First unknown of the top.
    top_unknown: usize,
    /// For each supernode below the top, where its kept values start ([`NOT_KEPT`]: none).
    base: Vec<usize>,
    /// Kept rows of the first part (those of the second follow).
    first_kept: usize,
    /// Kept rows of both parts.
    kept: usize,
}

impl SolveSplit {
    /// The split of `symbolic`, or `None` where it would not take [`MIN_SAVING`] of the work
    /// off the critical path (a chain-like tree, a small factor).
    pub(crate) fn of(symbolic: &SymbolicSupernodalCholesky<usize>) -> Option<Self> {
        let count = symbolic.n_supernodes();
        let begin = |s: usize| {
            symbolic
                .supernode_begin()
                .get(s)
                .copied()
                .unwrap_or(symbolic.nrows())
        };
        let mut supernode_of = vec![0usize; symbolic.nrows()];
        let mut work = Vec::with_capacity(count + 1);
        work.push(0usize);
        for s in 0..count {
            supernode_of[begin(s)..begin(s + 1)].fill(s);
            let (size, rows) = (
                begin(s + 1) - begin(s),
                symbolic.supernode(s).pattern().len(),
            );
            let entries = (size + rows) * size + size + rows;
            work.push(work[s] + entries);
        }
        let total = work[count];
        if total < MIN_WORK {
            return None;
        }
        let parent = |s: usize| {
            symbolic
                .supernode(s)
                .pattern()
                .first()
                .map(|&r| supernode_of[r])
        };
        // For each m, the least parent at or above m of a supernode below m.
        let mut parents = BinaryHeap::new();
        let mut best: Option<(usize, usize, usize)> = None;
        for m in 1..count {
            if let Some(p) = parent(m - 1) {
                parents.push(Reverse(p));
            }
            while parents.peek().is_some_and(|&Reverse(p)| p < m) {
                parents.pop();
            }
            let t = parents.peek().map_or(count, |&Reverse(p)| p);
            if t <= m {
                continue;
            }
            let critical = work[m].max(work[t] - work[m]) + (total - work[t]);
            if best.is_none_or(|(c, _, _)| critical < c) {
                best = Some((critical, m, t));
            }
        }
        let (critical, second, top) = best?;
        if (critical as f64) > (1.0 - MIN_SAVING) * total as f64 {
            return None;
        }
        let (second_unknown, top_unknown) = (begin(second), begin(top));
        // No first-part pattern row in the second part.
        let first_reaches_second = (0..second).any(|s| {
            symbolic
                .supernode(s)
                .pattern()
                .iter()
                .any(|r| (second_unknown..top_unknown).contains(r))
        });
        if first_reaches_second {
            return None;
        }
        let mut base = vec![NOT_KEPT; top];
        let (mut kept, mut first_kept) = (0, 0);
        for (s, slot) in base.iter_mut().enumerate() {
            if s == second {
                first_kept = kept;
            }
            if symbolic
                .supernode(s)
                .pattern()
                .last()
                .is_some_and(|&r| r >= top_unknown)
            {
                *slot = kept;
                kept += begin(s + 1) - begin(s);
            }
        }
        Some(Self {
            second,
            top,
            supernodes: count,
            second_unknown,
            top_unknown,
            base,
            first_kept,
            kept,
        })
    }

    /// The first part's supernodes.
    pub(crate) fn first_nodes(&self) -> Range<usize> {
        0..self.second
    }

    /// The second part's supernodes.
    pub(crate) fn second_nodes(&self) -> Range<usize> {
        self.second..self.top
    }

    /// The top's supernodes.
    pub(crate) fn top_nodes(&self) -> Range<usize> {
        self.top..self.supernodes
    }

    /// The second part's first unknown.
    pub(crate) fn second_unknown(&self) -> usize {
        self.second_unknown
    }

    /// The top's first unknown.
    pub(crate) fn top_unknown(&self) -> usize {
        self.top_unknown
    }

    /// For each supernode below the top, where its kept values start ([`NOT_KEPT`]: it has no
    /// pattern row in the top).
    pub(crate) fn kept_bases(&self) -> &[usize] {
        &self.base
    }

    /// The packed rows `x` (all unknowns) as the first part's, the second part's and the top's.
    pub(crate) fn parts_of<'x>(&self, x: &'x mut [Row]) -> [&'x mut [Row]; 3] {
        let (first, rest) = x.split_at_mut(self.second_unknown);
        let (second, top) = rest.split_at_mut(self.top_unknown - self.second_unknown);
        [first, second, top]
    }

    /// Room for the kept values of both parts.
    pub(crate) fn kept_buffer(&self) -> Vec<Row> {
        vec![[0.0; WIDTH]; self.kept]
    }

    /// `kept` (from [`Self::kept_buffer`]) as the first part's and the second part's.
    pub(crate) fn kept_parts<'k>(&'k self, kept: &'k mut [Row]) -> [KeptValues<'k>; 2] {
        let (first, second) = kept.split_at_mut(self.first_kept);
        [
            KeptValues {
                base: &self.base,
                first: 0,
                rows: first,
            },
            KeptValues {
                base: &self.base,
                first: self.first_kept,
                rows: second,
            },
        ]
    }
}
