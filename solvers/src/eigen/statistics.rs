//! [`SolverStatistics`]: what an eigen computation cost, phase by phase (factorizations, solves,
//! wall-clock and processor seconds), so that callers can check that every shift was factored
//! once and how well the phases use the machine's cores.

pub use crate::process_clock::process_cpu_seconds;
use crate::process_clock::{cpu_seconds_between, thread_cpu_seconds};
use std::ops::AddAssign;
use std::time::Instant;

/// The phases of an eigen computation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Inertia counts (`LDLᵀ` of `A − tM`) at thresholds and interval boundaries.
    Counting,
    /// Krylov–Schur iterations of the spectrum intervals, with the inverse-iteration step on
    /// all locked vectors, their Rayleigh–Ritz against `A` and their refinement, then the
    /// assembly of the eigenvectors and their residual check.
    Solving,
    /// Inverse-iteration refinement of the eigenpairs whose residual misses the target, made by
    /// each interval's job right after its Krylov–Schur solve (inside the solving phase).
    Refinement,
}

/// The cost of one phase.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PhaseStatistics {
    /// Numeric sparse factorizations (one per shift; a shift nudged off an eigenvalue counts again).
    pub factorizations: usize,
    /// Single-vector solves with a factorization (a block of `r` counts `r`).
    pub solves: usize,
    /// Wall-clock seconds.
    pub wall_seconds: f64,
    /// Processor seconds of the whole process (user + system, every thread) during the phase;
    /// `cpu_seconds / wall_seconds` is the number of cores the phase kept busy on average
    /// (other work of the same process running at the same time counts too). NaN where the
    /// platform has no processor-time clock ([`crate::process_clock`]).
    pub cpu_seconds: f64,
}

impl PhaseStatistics {
    /// Average number of busy cores: `cpu_seconds / wall_seconds` (0 for an empty phase).
    pub fn utilisation(&self) -> f64 {
        if self.wall_seconds > 0.0 {
            self.cpu_seconds / self.wall_seconds
        } else {
            0.0
        }
    }
}

impl AddAssign for PhaseStatistics {
    fn add_assign(&mut self, other: Self) {
        self.factorizations += other.factorizations;
        self.solves += other.solves;
        self.wall_seconds += other.wall_seconds;
        self.cpu_seconds += other.cpu_seconds;
    }
}

/// The cost of an eigen computation by phase.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolverStatistics {
    /// Inertia counts.
    pub counting: PhaseStatistics,
    /// Krylov–Schur iterations, refinement, assembly and residual check.
    pub solving: PhaseStatistics,
    /// Refinement of eigenpairs that missed the residual target. It runs inside the solving
    /// phase (each interval refines its own pairs with its own factorization), so its
    /// `wall_seconds` and `cpu_seconds` are summed over the threads that refined, and are part of
    /// the solving phase's seconds, not added to them.
    pub refinement: PhaseStatistics,
    /// Eigenpairs that were refined (the others met the target after the inverse-iteration step
    /// every interval makes on all its pairs, whose solves count in the solving phase).
    pub refined_pairs: usize,
    /// The largest estimated work memory of the intervals solved at the same time, in bytes
    /// (see [`super::EigenOptions::slice_memory`]; an estimate from the slices' sizes, not a
    /// measurement).
    pub peak_slice_memory: usize,
}

impl SolverStatistics {
    /// Factorizations of all phases.
    pub fn factorizations(&self) -> usize {
        self.counting.factorizations + self.solving.factorizations + self.refinement.factorizations
    }

    /// Solves of all phases.
    pub fn solves(&self) -> usize {
        self.counting.solves + self.solving.solves + self.refinement.solves
    }

    /// The statistics of `phase`.
    pub fn phase(&self, phase: Phase) -> PhaseStatistics {
        match phase {
            Phase::Counting => self.counting,
            Phase::Solving => self.solving,
            Phase::Refinement => self.refinement,
        }
    }

    /// One line per phase (counting, solving, refinement), each indented by two spaces and
    /// ending in a newline: its factorizations, solves, wall seconds and average processor use
    /// (`100 ·` [`PhaseStatistics::utilisation`], % CPU).
    pub fn phase_table(&self) -> String {
        [
            ("counting", self.counting),
            ("solving", self.solving),
            ("refinement", self.refinement),
        ]
        .iter()
        .map(|(phase, p)| {
            format!(
                "  {phase:<10} {:>3} factorizations {:>6} solves {:>8.2} s wall {:>5.0} % CPU\n",
                p.factorizations,
                p.solves,
                p.wall_seconds,
                100.0 * p.utilisation()
            )
        })
        .collect()
    }

    /// The statistics of `phase`, to change.
    pub fn phase_mut(&mut self, phase: Phase) -> &mut PhaseStatistics {
        match phase {
            Phase::Counting => &mut self.counting,
            Phase::Solving => &mut self.solving,
            Phase::Refinement => &mut self.refinement,
        }
    }
}

impl AddAssign for SolverStatistics {
    fn add_assign(&mut self, other: Self) {
        self.counting += other.counting;
        self.solving += other.solving;
        self.refinement += other.refinement;
        self.refined_pairs += other.refined_pairs;
        self.peak_slice_memory = self.peak_slice_memory.max(other.peak_slice_memory);
    }
}

/// Wall-clock and process processor time since it was started.
pub(crate) struct PhaseClock {
    wall: Instant,
    cpu: f64,
}

impl PhaseClock {
    pub(crate) fn start() -> Self {
        Self {
            wall: Instant::now(),
            cpu: process_cpu_seconds(),
        }
    }

    /// Adds the elapsed wall-clock and processor seconds to `statistics`.
    pub(crate) fn stop(self, statistics: &mut PhaseStatistics) {
        statistics.wall_seconds += self.wall.elapsed().as_secs_f64();
        statistics.cpu_seconds += cpu_seconds_between(self.cpu, process_cpu_seconds());
    }
}

/// Wall-clock and processor time of the calling thread since it was started.
pub(crate) struct ThreadClock {
    wall: Instant,
    cpu: f64,
}

impl ThreadClock {
    pub(crate) fn start() -> Self {
        Self {
            wall: Instant::now(),
            cpu: thread_cpu_seconds(),
        }
    }

    /// `(wall-clock seconds, processor seconds of this thread)` since the start.
    pub(crate) fn elapsed(&self) -> (f64, f64) {
        (
            self.wall.elapsed().as_secs_f64(),
            cpu_seconds_between(self.cpu, thread_cpu_seconds()),
        )
    }
}
