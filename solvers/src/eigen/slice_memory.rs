//! The memory budget of the spectrum slices that run at the same time: each interval's job
//! holds a Krylov basis, its locked vectors and the packed operator buffers, all `n` rows tall
//! ([`slice_bytes`]), and at a million faces two of them took most of the peak (two slices of
//! the co-potential pencil, `n = 1,532,520`: 4.4 GB each; see `docs/performance.md`). The
//! budget ([`EigenOptions::slice_memory`](super::EigenOptions::slice_memory)) binds in two
//! places:
//!
//! - an interval's target size is lowered so that one slice fits in it
//!   ([`interval_size_within`]; more, smaller intervals cost factorizations and solves, so this
//!   only happens when a single slice would not fit);
//! - a job starts only when its slice fits next to the ones running ([`MemoryGate`]); one that
//!   does not waits (its thread helps the running jobs' parallel products meanwhile), and a
//!   later job that fits (an interval of a smaller pencil) may start first. A job always starts
//!   when nothing else runs.
//!
//! The default ([`default_slice_memory`]) is a sixth of the machine's physical memory (4 GiB
//! on 24 GiB), so that on a small mesh it never binds; the command line's `TVF_SLICE_MEMORY`
//! (bytes, with an optional binary suffix `K`, `M`, `G` or `T`) overrides it for the process
//! ([`set_default_slice_memory`]).

use super::krylov_slice::{basis_columns, locked_columns};
use crate::packed_rows::WIDTH;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex, MutexGuard};
use std::time::Duration;

/// The process-wide default budget set by [`set_default_slice_memory`] (0: none set).
static DEFAULT_BUDGET: AtomicUsize = AtomicUsize::new(0);

/// The fraction of physical memory the concurrent slices may take by default (a sixth: on a
/// 24 GiB machine 4 GiB, which at a million faces holds one co-potential slice, about 4.1 GB,
/// alone; the factorizations, the mesh, the pencils and the eigenvectors in flight take about
/// as much again).
const DEFAULT_SHARE_OF_MEMORY: usize = 6;

/// The budget when the physical memory is unknown (no `/proc/meminfo`): 4 GiB.
const FALLBACK_BUDGET: usize = 4 << 30;

/// Estimated bytes of the work memory of one slice of dimension `n` that must find `wanted`
/// eigenpairs in blocks of `block` vectors: the Krylov basis (`2·wanted + 4·block` expanded
/// columns and three unexpanded blocks, see `krylov_slice.rs`), the locked vectors
/// (`wanted + 2·block` columns) and the two packed operator buffers (`WIDTH` columns each), all
/// of `n` rows of `f64`.
pub(crate) fn slice_bytes(n: usize, wanted: usize, block: usize) -> usize {
    let columns = basis_columns(wanted, block) + locked_columns(wanted, block) + 2 * WIDTH;
    n.saturating_mul(columns).saturating_mul(size_of::<f64>())
}

/// The target interval size for a pencil of dimension `n`: `interval_size`, or less where one
/// slice of that size would exceed `budget` bytes ([`slice_bytes`]), but at least `2·block`.
pub(crate) fn interval_size_within(
    n: usize,
    block: usize,
    interval_size: usize,
    budget: usize,
) -> usize {
    let floor = 2 * block;
    if slice_bytes(n, interval_size, block) <= budget {
        return interval_size.max(floor);
    }
    let columns = budget / (size_of::<f64>() * n.max(1));
    let fitting = columns.saturating_sub(9 * block + 2 * WIDTH) / 3;
    fitting.clamp(floor, interval_size.max(floor))
}

/// The budget of a computation whose [`EigenOptions::slice_memory`](super::EigenOptions) is
/// `None`: the one set by [`set_default_slice_memory`], else a sixth of the physical memory
/// (`MemTotal` of `/proc/meminfo`), else 4 GiB.
pub fn default_slice_memory() -> usize {
    match DEFAULT_BUDGET.load(Ordering::Relaxed) {
        0 => physical_memory().map_or(FALLBACK_BUDGET, |m| m / DEFAULT_SHARE_OF_MEMORY),
        set => set,
    }
}

/// Sets the process-wide default of [`default_slice_memory`] in bytes (`None`: back to the
/// share of physical memory). The command line sets it from `TVF_SLICE_MEMORY`.
pub fn set_default_slice_memory(bytes: Option<usize>) {
    DEFAULT_BUDGET.store(bytes.unwrap_or(0), Ordering::Relaxed);
}

/// Bytes from a decimal number with an optional binary suffix (`K`, `M`, `G`, `T`, optionally
/// followed by `iB` or `B`; case-insensitive), e.g. `4G` = 4 GiB.
pub fn parse_byte_count(text: &str) -> Option<usize> {
    let text = text.trim();
    let upper = text.to_ascii_uppercase();
    let number_end = upper
        .find(|c: char| !c.is_ascii_digit() && c != '.')
        .unwrap_or(upper.len());
    let (number, unit) = upper.split_at(number_end);
    let shift = match unit.trim_end_matches("IB").trim_end_matches('B') {
        "" => 0,
        "K" => 10,
        "M" => 20,
        "G" => 30,
        "T" => 40,
        _ => return None,
    };
    let value: f64 = number.parse().ok()?;
    let bytes = value * (1u64 << shift) as f64;
    (bytes.is_finite() && bytes >= 1.0 && bytes < usize::MAX as f64).then_some(bytes as usize)
}

/// `MemTotal` of `/proc/meminfo` in bytes (Linux), `None` elsewhere.
fn physical_memory() -> Option<usize> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: usize = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// A job admitted by [`MemoryGate::admit`]; its memory is given back to the gate when this is
/// dropped (also when the job unwinds, so that no other job waits for it forever).
pub(crate) struct Admission<'g> {
    gate: &'g MemoryGate,
    /// The job's index.
    pub(crate) job: usize,
}

impl Drop for Admission<'_> {
    fn drop(&mut self) {
        self.gate.release(self.job);
    }
}

/// Admits jobs (in their order) while their estimated memory fits in the budget next to the
/// jobs running; see the module documentation.
pub(crate) struct MemoryGate {
    budget: usize,
    costs: Vec<usize>,
    state: Mutex<GateState>,
    released: Condvar,
}

struct GateState {
    started: Vec<bool>,
    in_use: usize,
    running: usize,
    /// The largest sum of running jobs' estimates so far.
    peak: usize,
}

impl MemoryGate {
    /// A gate for jobs of estimated memory `costs` (bytes, one per job) within `budget` bytes.
    pub(crate) fn new(budget: usize, costs: Vec<usize>) -> Self {
        let jobs = costs.len();
        Self {
            budget,
            costs,
            state: Mutex::new(GateState {
                started: vec![false; jobs],
                in_use: 0,
                running: 0,
                peak: 0,
            }),
            released: Condvar::new(),
        }
    }

    /// The next job to run: the first not yet started whose memory fits next to the running
    /// jobs' (any, when none runs); `None` once every job has started or `stop` is set. While
    /// none fits, waits for a job to end, running other tasks of rayon's pool meanwhile (the
    /// running jobs' parallel products) when called from inside it.
    pub(crate) fn admit(&self, stop: &AtomicBool) -> Option<Admission<'_>> {
        loop {
            let mut state = self.lock();
            if stop.load(Ordering::Relaxed) {
                return None;
            }
            let mut unstarted = (0..self.costs.len()).filter(|&j| !state.started[j]);
            let first = unstarted.next()?;
            let fits = |j: usize| state.running == 0 || state.in_use + self.costs[j] <= self.budget;
            let chosen = std::iter::once(first).chain(unstarted).find(|&j| fits(j));
            if let Some(job) = chosen {
                state.started[job] = true;
                state.in_use += self.costs[job];
                state.running += 1;
                state.peak = state.peak.max(state.in_use);
                return Some(Admission { gate: self, job });
            }
            if rayon::current_thread_index().is_some() {
                drop(state);
                if !matches!(rayon::yield_now(), Some(rayon::Yield::Executed)) {
                    std::thread::sleep(Duration::from_millis(2));
                }
            } else {
                let _ = self
                    .released
                    .wait_timeout(state, Duration::from_millis(50))
                    .unwrap_or_else(|poisoned| poisoned.into_inner());
            }
        }
    }

    /// Marks `job` (admitted before) as ended: its memory is free for the next.
    fn release(&self, job: usize) {
        let mut state = self.lock();
        state.in_use -= self.costs[job];
        state.running -= 1;
        drop(state);
        self.released.notify_all();
    }

    /// The largest estimated memory of the jobs that ran at the same time, in bytes.
    pub(crate) fn peak(&self) -> usize {
        self.lock().peak
    }

    fn lock(&self) -> MutexGuard<'_, GateState> {
        // A panic in a job leaves consistent counts (they change under the lock only).
        self.state
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_counts_with_binary_suffixes() {
        assert_eq!(parse_byte_count("1024"), Some(1024));
        assert_eq!(parse_byte_count("4G"), Some(4 << 30));
        assert_eq!(parse_byte_count("512m"), Some(512 << 20));
        assert_eq!(parse_byte_count("1.5GiB"), Some(3 << 29));
        assert_eq!(parse_byte_count(" 2KB "), Some(2048));
        assert_eq!(parse_byte_count("4X"), None);
        assert_eq!(parse_byte_count("G"), None);
        assert_eq!(parse_byte_count("0"), None);
        assert_eq!(parse_byte_count("-1G"), None);
    }

    /// The interval size is kept while a slice fits, lowered to fit, and never below two
    /// blocks.
    #[test]
    fn interval_size_shrinks_only_to_fit_the_budget() {
        let (n, block) = (1_000_000, 8);
        let full = slice_bytes(n, 96, block);
        assert_eq!(interval_size_within(n, block, 96, full), 96);
        assert_eq!(interval_size_within(n, block, 96, usize::MAX), 96);
        let half = interval_size_within(n, block, 96, full / 2);
        assert!((16..96).contains(&half), "{half}");
        assert!(slice_bytes(n, half, block) <= full / 2);
        assert!(slice_bytes(n, half + 1, block) > full / 2);
        assert_eq!(interval_size_within(n, block, 96, 1), 16);
    }

    /// Jobs start in order while they fit; one that does not waits and a later one that fits
    /// goes first; a lone job always starts.
    #[test]
    fn admits_jobs_that_fit_next_to_the_running_ones() {
        let stop = AtomicBool::new(false);
        let gate = MemoryGate::new(10, vec![6, 6, 3, 20]);
        let job = |admitted: &Option<Admission<'_>>| admitted.as_ref().map(|a| a.job);
        let first = gate.admit(&stop);
        assert_eq!(job(&first), Some(0));
        let second = gate.admit(&stop);
        assert_eq!(job(&second), Some(2), "job 1 does not fit beside job 0");
        drop((first, second));
        let third = gate.admit(&stop);
        assert_eq!(job(&third), Some(1));
        drop(third);
        let alone = gate.admit(&stop);
        assert_eq!(job(&alone), Some(3), "alone, a job over the budget runs");
        drop(alone);
        assert!(gate.admit(&stop).is_none());
        assert_eq!(gate.peak(), 20);
        let stopped = MemoryGate::new(10, vec![1]);
        stop.store(true, Ordering::Relaxed);
        assert!(stopped.admit(&stop).is_none());
    }
}
