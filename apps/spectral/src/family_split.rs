//! [`split_families`]: how many non-zero eigenpairs of the potential and of the co-potential
//! Laplacian a basis request needs, counted exactly up front by Sylvester's law of inertia.
//!
//! The number of eigenvalues of `(A, M)` strictly below `t` equals the number of negative pivots
//! of an `LDLᵀ` factorization of `A − tM`. If the two families together have at least `m`
//! non-zero eigenvalues below `t`, solving each family for exactly its own count computes every
//! eigenvalue of both below `t`, hence provably the `m` lowest of their union: no family has to
//! be guessed generously or solved a second time.

use crate::basis_request::BasisSize;
use crate::dense_memory::check_dense_memory;
use crate::scalar_spectrum::ScalarSpectrum;
use crate::BasisError;
use std::f64::consts::PI;
use std::time::Instant;
use tvf_solvers::{EigenOptions, Pencil, ShiftCount, SolverError};

/// Relative margin above a [`BasisSize::MaxEigenvalue`] bound at which eigenvalues are counted,
/// so that an eigenvalue equal to the bound up to round-off is computed (and then kept, the
/// bound being inclusive, if its computed value is `≤ bound`).
const INCLUSIVE_MARGIN: f64 = 1e-9;
/// Relative tolerance of [`FamilySplit::check`]: a computed eigenvalue counted below `t` may come
/// out of the eigensolver this much above `t` (eigenvalues are accurate to ~1e-12 relative).
const COVERAGE_TOLERANCE: f64 = 1e-8;
/// Inertia counts (each one factorization per family) the threshold search may spend.
const MAX_EVALUATIONS: usize = 12;
/// Evaluations after which the search bisects instead of interpolating (interpolation on a
/// staircase can stall at a cluster of eigenvalues).
const BISECT_AFTER: usize = 7;
/// Recounts of the family with the lower shift when the two families' shifts were nudged apart
/// (each pencil nudges a shift that is one of its eigenvalues upwards on its own).
const MAX_ALIGNMENTS: usize = 4;

/// How many non-zero eigenpairs of each family to compute, and what counting them cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FamilySplit {
    /// Non-zero eigenpairs of the potential problem `(d0ᵀ M1 d0, M0)`.
    pub potential: usize,
    /// Non-zero eigenpairs of the co-potential problem `(d1 M1⁻¹ d1ᵀ, M2⁻¹)`.
    pub co_potential: usize,
    /// When the counts come from inertia: the threshold `t` (units of λ, 1/length²) such that the
    /// counts are exactly the non-zero eigenvalues of each family strictly below `t`. `None` for
    /// counts fixed by the request (pairs, complete, tiny problems solved densely).
    pub threshold: Option<f64>,
    /// Numeric `LDLᵀ` factorizations spent counting (both families).
    pub factorizations: usize,
    /// The counts of both families at the threshold (kernel included), for the eigensolver's
    /// top shift: `None` when the counts are fixed by the request.
    pub tops: Option<(ShiftCount, ShiftCount)>,
    /// Wall-clock seconds spent counting.
    pub seconds: f64,
}

impl FamilySplit {
    fn fixed(potential: usize, co_potential: usize) -> Self {
        Self {
            potential,
            co_potential,
            threshold: None,
            factorizations: 0,
            tops: None,
            seconds: 0.0,
        }
    }

    /// Checks that the eigensolver's non-zero eigenvalues `values` (ascending) of `family` are
    /// the `requested` ones this split counted: as many as requested and, for inertia counts,
    /// all below the threshold. Any other outcome means the request is not covered.
    ///
    /// Errors: [`BasisError::Eigen`] (with [`SolverError::NoConvergence`]) describing the gap.
    pub fn check(
        &self,
        family: &ScalarSpectrum,
        values: &[f64],
        requested: usize,
    ) -> Result<(), BasisError> {
        let uncovered = |reason: String| BasisError::Eigen {
            problem: family.name,
            source: SolverError::NoConvergence { reason },
        };
        if values.len() != requested {
            return Err(uncovered(format!(
                "{requested} eigenpairs were needed to cover the request, but {} were computed",
                values.len()
            )));
        }
        if let (Some(t), Some(&last)) = (self.threshold, values.last()) {
            if last > t * (1.0 + COVERAGE_TOLERANCE) {
                return Err(uncovered(format!(
                    "the inertia count put {requested} non-zero eigenvalues below {t:e}, but the \
                     eigensolver's {requested}-th is {last:e}: eigenvalues below it are missing"
                )));
            }
        }
        Ok(())
    }
}

/// The number of non-zero eigenpairs of each family that `size` needs (`harmonic` = `2g`
/// harmonic fields come first; `area` = total surface area, for Weyl's law).
///
/// - `Pairs(k)`: `k` of each (fewer if a family has fewer); `Complete`: all of both.
/// - `Fields(d)`, `m = d − 2g`: a threshold `t` with at least `m` non-zero eigenvalues of the
///   two families below it, found by inertia counts (both families factored in parallel) from
///   Weyl's estimate `t ≈ 2πm / area` by secant steps and bisection, aiming at an excess of at
///   most `max(1, m/250)` eigenpairs and stopping early once the bracket around the `m`-th
///   eigenvalue is about one eigenvalue wide (Weyl), when a cluster straddles position `m`;
///   each family's count below `t`. The upper bound of both spectra is estimated only where the
///   search needs it (see [`PairCounter::threshold_for`]).
/// - `MaxEigenvalue(bound)`: each family's count of non-zero eigenvalues below
///   `bound · (1 + 1e-9)` (one count).
///
/// Tiny problems (both at most the eigensolver's dense threshold) are solved completely: a dense
/// eigensolver finds all eigenpairs at the cost of a few, so counting would only add time.
///
/// Errors: [`BasisError::InvalidRequest`] for more fields than the space has or a negative or
/// non-finite bound; [`BasisError::Eigen`] if a factorization fails.
pub(crate) fn split_families(
    size: BasisSize,
    harmonic: usize,
    (potential, potential_pencil): (&ScalarSpectrum, &Pencil<'_>),
    (co_potential, co_potential_pencil): (&ScalarSpectrum, &Pencil<'_>),
    area: f64,
) -> Result<FamilySplit, BasisError> {
    let start = Instant::now();
    let (available_a, available_b) = (potential.available(), co_potential.available());
    let dense_threshold = EigenOptions::default().dense_threshold;
    let tiny =
        potential.dimension() <= dense_threshold && co_potential.dimension() <= dense_threshold;
    let counter = PairCounter {
        potential: (potential, potential_pencil),
        co_potential: (co_potential, co_potential_pencil),
    };
    // Above every eigenvalue of both families: all eigenvalues are below it, uncounted. Both
    // bounds at once: without a diagonal mass each is a Lanczos run of its own (40 solves with
    // the mass, or with `W` for a mixed pencil), so it is made only where it is needed.
    let ceiling = || {
        let (a, b) = rayon::join(
            || potential.eigenvalue_upper_bound(potential_pencil),
            || co_potential.eigenvalue_upper_bound(co_potential_pencil),
        );
        a.max(b) * (1.0 + INCLUSIVE_MARGIN)
    };
    let (threshold, counts) = match size {
        BasisSize::Pairs(k) => {
            return Ok(FamilySplit::fixed(k.min(available_a), k.min(available_b)))
        }
        BasisSize::Complete => {
            check_dense_memory(potential.dimension(), co_potential.dimension())?;
            return Ok(FamilySplit::fixed(available_a, available_b));
        }
        BasisSize::Fields(d) => {
            let total = harmonic + available_a + available_b;
            if d > total {
                return Err(BasisError::InvalidRequest(format!(
                    "{d} fields requested, but the field space has only {total} eigenfields"
                )));
            }
            let m = d.saturating_sub(harmonic);
            if m == 0 {
                return Ok(FamilySplit::fixed(0, 0));
            }
            if tiny || m >= available_a + available_b {
                return Ok(FamilySplit::fixed(available_a, available_b));
            }
            let weyl = weyl_shift(m, area);
            counter.threshold_for(m, &ceiling, weyl)?
        }
        BasisSize::MaxEigenvalue(bound) => {
            if !bound.is_finite() || bound < 0.0 {
                return Err(BasisError::InvalidRequest(format!(
                    "eigenvalue bound {bound} must be finite and non-negative"
                )));
            }
            if bound == 0.0 {
                // Every non-zero eigenvalue of a positive semidefinite problem is positive.
                return Ok(FamilySplit::fixed(0, 0));
            }
            let t = bound * (1.0 + INCLUSIVE_MARGIN);
            if tiny || t >= ceiling() {
                return Ok(FamilySplit::fixed(available_a, available_b));
            }
            let (shift, a, b) = counter.nonzero_below(t)?;
            (shift, (a, b))
        }
    };
    // Both counts at the threshold are remembered by the pencils: no new factorization.
    let tops = (
        potential_pencil.count_below(threshold),
        co_potential_pencil.count_below(threshold),
    );
    let tops = match tops {
        (Ok(a), Ok(b)) => (a, b),
        (Err(source), _) | (_, Err(source)) => {
            return Err(BasisError::Eigen {
                problem: potential.name,
                source,
            })
        }
    };
    Ok(FamilySplit {
        potential: counts.0,
        co_potential: counts.1,
        threshold: Some(threshold),
        factorizations: counter.factorizations(),
        tops: Some(tops),
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// The first trial threshold for `m` non-zero eigenvalues of both families on a surface of total
/// area `area`: by Weyl's law on a closed surface each family has about `area·t/(4π)` eigenvalues
/// below `t`, aiming at `m` plus half the search's slack (see [`PairCounter::threshold_for`]).
fn weyl_shift(m: usize, area: f64) -> f64 {
    search_goal(m).1 * 2.0 * PI / area
}

/// The excess of eigenpairs the threshold search for `m` accepts (`max(1, m/250)`) and the count
/// it aims at, `m` plus half that.
fn search_goal(m: usize) -> (usize, f64) {
    let slack = (m / 250).max(1);
    (slack, m as f64 + slack as f64 / 2.0)
}

/// Counts of both families at the same shift, computed in parallel by their pencils (which
/// remember every shift, so the eigensolver does not factor a counted one again).
struct PairCounter<'p, 'a> {
    potential: (&'p ScalarSpectrum, &'p Pencil<'a>),
    co_potential: (&'p ScalarSpectrum, &'p Pencil<'a>),
}

impl PairCounter<'_, '_> {
    /// `(shift, a, b)`: the non-zero eigenvalues `a` of the potential and `b` of the
    /// co-potential problem strictly below `shift`, where `shift ≥ t` is `t`, nudged upward by
    /// a pencil while it is an eigenvalue to working precision (and the other family recounted
    /// there, so that both counts hold at the same shift).
    fn nonzero_below(&self, t: f64) -> Result<(f64, usize, usize), BasisError> {
        let count = |(spectrum, pencil): (&ScalarSpectrum, &Pencil<'_>), shift: f64| {
            pencil
                .count_below(shift)
                .map_err(|source| BasisError::Eigen {
                    problem: spectrum.name,
                    source,
                })
        };
        let (a, b) = rayon::join(|| count(self.potential, t), || count(self.co_potential, t));
        let (mut a, mut b) = (a?, b?);
        for _ in 0..MAX_ALIGNMENTS {
            if a.shift < b.shift {
                a = count(self.potential, b.shift)?;
            } else if b.shift < a.shift {
                b = count(self.co_potential, a.shift)?;
            } else {
                return Ok((
                    a.shift,
                    a.below.saturating_sub(self.potential.0.components()),
                    b.below.saturating_sub(self.co_potential.0.components()),
                ));
            }
        }
        Err(BasisError::Eigen {
            problem: self.potential.0.name,
            source: SolverError::NoConvergence {
                reason: format!(
                    "the two families' shifts near {t:e} could not be brought together (both \
                     are eigenvalues to working precision)"
                ),
            },
        })
    }

    /// Counting factorizations of both pencils so far.
    fn factorizations(&self) -> usize {
        self.potential.1.statistics().counting.factorizations
            + self.co_potential.1.statistics().counting.factorizations
    }

    /// `(t, (a, b))` with `a + b ≥ m` non-zero eigenvalues of the two families below `t` and
    /// `a + b − m` small (see [`split_families`]), searched from `weyl` ([`weyl_shift`]).
    /// `ceiling` gives a shift above every eigenvalue of both; it is called (once) only where a
    /// count has every eigenvalue below its shift, or the search must bisect before any count
    /// has reached `m`, or runs out of counts without one: for a pencil without a diagonal mass
    /// it is a Lanczos run of 40 solves, which on `bunny-closed.obj` with Galerkin masses took
    /// longer than the counts it stood beside.
    fn threshold_for(
        &self,
        m: usize,
        ceiling: &dyn Fn() -> f64,
        weyl: f64,
    ) -> Result<(f64, (usize, usize)), BasisError> {
        let all = (
            self.potential.0.available(),
            self.co_potential.0.available(),
        );
        let ceiling = {
            let estimate = std::cell::OnceCell::new();
            move || *estimate.get_or_init(ceiling)
        };
        let (slack, goal) = search_goal(m);
        // Lowest shift with at least m below it, highest with fewer.
        let mut high: Option<(f64, (usize, usize))> = None;
        let mut low: Option<(f64, usize)> = None;
        let mut t = weyl;
        for evaluation in 0..MAX_EVALUATIONS {
            let (shift, a, b) = self.nonzero_below(t)?;
            let count = a + b;
            if count >= m {
                if high.is_none_or(|(h, _)| shift < h) {
                    high = Some((shift, (a, b)));
                }
                if count <= m + slack {
                    break;
                }
            } else if low.is_none_or(|(l, _)| shift > l) {
                low = Some((shift, count));
            }
            let floor = low.map_or(0.0, |(l, _)| l);
            if let Some((h, _)) = high {
                if (h - floor) * goal <= h {
                    // By Weyl's law the bracket holds about one eigenvalue: a narrower one
                    // would not remove excess (a cluster of close eigenvalues straddles
                    // position m).
                    break;
                }
            }
            t = match (low, high) {
                // Secant step between the bracket's ends (the count is nearly linear in t).
                (Some((l, lc)), Some((h, (ha, hb)))) => {
                    l + (goal - lc as f64) * (h - l) / (ha + hb - lc) as f64
                }
                // Every eigenvalue lies below the shift, which then says nothing of the
                // spectrum's scale (Weyl's shift on a small mesh asked for nearly all its
                // eigenvalues): go on from half the ceiling if that is lower.
                _ if count == all.0 + all.1 => (0.5 * ceiling()).min(shift * goal / count as f64),
                // Counts grow about in proportion to t (Weyl): rescale the last shift.
                _ if count > 0 => shift * goal / count as f64,
                _ => 4.0 * shift,
            };
            if evaluation + 1 >= BISECT_AFTER || !(t > floor && high.is_none_or(|(h, _)| t < h)) {
                t = 0.5 * (floor + high.map_or_else(&ceiling, |(h, _)| h));
            }
        }
        // Without a count reaching m, the ceiling has them all.
        Ok(high.unwrap_or_else(|| (ceiling(), all)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::discretization::sparse::from_triplets;
    use tvf_core::discretization::{EigenStiffness, Eigenproblem, Mass};

    /// The graph Laplacian of a path with `n` nodes and unit masses: eigenvalues
    /// `2 − 2 cos(kπ/n)`, `k = 0..n`, one zero (one component).
    fn path(n: usize) -> ScalarSpectrum {
        let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
        for i in 0..n - 1 {
            for (r, c, v) in [
                (i, i, 1.0),
                (i + 1, i + 1, 1.0),
                (i, i + 1, -1.0),
                (i + 1, i, -1.0),
            ] {
                rows.push(r);
                cols.push(c);
                values.push(v);
            }
        }
        let problem = Eigenproblem {
            stiffness: EigenStiffness::Sparse(from_triplets(n, n, rows, cols, values)),
            mass: Mass::diagonal("unit mass", vec![1.0; n]).unwrap(),
        };
        ScalarSpectrum::new("path", problem, &vec![true; n], &[], 1)
    }

    fn nonzero_eigenvalues_below(n: usize, t: f64) -> usize {
        (1..n)
            .filter(|&k| 2.0 - 2.0 * (k as f64 * PI / n as f64).cos() < t)
            .count()
    }

    #[test]
    fn counts_match_the_closed_form_spectrum_and_shifts_on_eigenvalues_are_nudged() {
        let (a, b) = (path(40), path(63));
        let (pa, pb) = (a.pencil().unwrap(), b.pencil().unwrap());
        let counter = PairCounter {
            potential: (&a, &pa),
            co_potential: (&b, &pb),
        };
        for t in [0.01, 0.5, 1.3, 3.9] {
            assert_eq!(
                counter.nonzero_below(t).unwrap(),
                (
                    t,
                    nonzero_eigenvalues_below(40, t),
                    nonzero_eigenvalues_below(63, t)
                )
            );
        }
        // Counted shifts are remembered: no new factorization.
        let before = counter.factorizations();
        counter.nonzero_below(0.5).unwrap();
        assert_eq!(counter.factorizations(), before);
        // 2 is an eigenvalue of the 40-node path (k = 20): its LDLᵀ has an exactly zero pivot
        // (integer arithmetic on a tree), so the shift moves up and the eigenvalue counts.
        let (shift, below_a, below_b) = counter.nonzero_below(2.0).unwrap();
        assert!(shift > 2.0 && shift < 2.0 + 1e-6, "{shift}");
        assert_eq!(below_a, 20);
        assert_eq!(below_b, nonzero_eigenvalues_below(63, shift));
        assert!(counter.factorizations() > 10);
    }

    #[test]
    fn thresholds_cover_the_request_with_little_excess() {
        let (a, b) = (path(120), path(300));
        let bound = a
            .eigenvalue_upper_bound(&a.pencil().unwrap())
            .max(b.eigenvalue_upper_bound(&b.pencil().unwrap()));
        assert!(bound >= 4.0);
        let estimates = std::cell::Cell::new(0);
        let ceiling = || {
            estimates.set(estimates.get() + 1);
            bound
        };
        // For a unit area Weyl's shift lies above both spectra (below 4) for every m; the
        // second area puts it inside them (m = 420 at 4).
        for (area, m) in [1.0, 660.0]
            .into_iter()
            .flat_map(|area| [1, 7, 100, 250, 418].map(|m| (area, m)))
        {
            estimates.set(0);
            let (pa, pb) = (a.pencil().unwrap(), b.pencil().unwrap());
            let counter = PairCounter {
                potential: (&a, &pa),
                co_potential: (&b, &pb),
            };
            // Weyl's law does not hold for paths: the search must still get there.
            let weyl = weyl_shift(m, area);
            let (t, (below_a, below_b)) = counter.threshold_for(m, &ceiling, weyl).unwrap();
            assert_eq!(
                below_a,
                nonzero_eigenvalues_below(120, t),
                "m = {m}, area {area}"
            );
            assert_eq!(
                below_b,
                nonzero_eigenvalues_below(300, t),
                "m = {m}, area {area}"
            );
            assert!(below_a + below_b >= m, "m = {m}, area {area}");
            assert!(
                below_a + below_b <= m + 3,
                "m = {m}, area {area}: {below_a} + {below_b}"
            );
            // At most MAX_EVALUATIONS counts, plus a nudge or two where bisection lands on
            // eigenvalues with simple closed forms (1, 2, 3 are eigenvalues of both paths).
            assert!(
                counter.factorizations() <= 2 * (MAX_EVALUATIONS + 2),
                "m = {m}, area {area}"
            );
            // The ceiling only where Weyl's shift had every eigenvalue below it (m = 418 is
            // all of them: that first count is the answer).
            let saturated = weyl >= 4.0 && m < 418;
            assert_eq!(
                estimates.get(),
                usize::from(saturated),
                "m = {m}, area {area}"
            );
        }
    }

    #[test]
    fn the_ceiling_is_estimated_where_the_search_bisects_without_an_upper_end() {
        // A start far below both spectra (their lowest eigenvalues are about 6e-3 and 2.5e-3):
        // counts of zero quadruple the shift, and from the seventh count on the search
        // bisects, up to the ceiling while no count has reached m; the ceiling is estimated
        // once however often the bisection asks for it.
        let (a, b) = (path(40), path(63));
        let (pa, pb) = (a.pencil().unwrap(), b.pencil().unwrap());
        let counter = PairCounter {
            potential: (&a, &pa),
            co_potential: (&b, &pb),
        };
        let estimates = std::cell::Cell::new(0);
        let ceiling = || {
            estimates.set(estimates.get() + 1);
            4.5
        };
        let m = 90;
        let (t, (below_a, below_b)) = counter.threshold_for(m, &ceiling, 1e-9).unwrap();
        assert_eq!(estimates.get(), 1);
        assert_eq!(below_a, nonzero_eigenvalues_below(40, t));
        assert_eq!(below_b, nonzero_eigenvalues_below(63, t));
        assert!(below_a + below_b >= m);
    }

    #[test]
    fn checks_reject_missing_eigenpairs() {
        let spectrum = path(10);
        let split = FamilySplit {
            potential: 3,
            co_potential: 0,
            threshold: Some(1.0),
            factorizations: 2,
            tops: None,
            seconds: 0.0,
        };
        assert!(split.check(&spectrum, &[0.1, 0.4, 0.9], 3).is_ok());
        assert!(split.check(&spectrum, &[0.1, 0.4], 3).is_err());
        assert!(split.check(&spectrum, &[0.1, 0.4, 1.5], 3).is_err());
        let fixed = FamilySplit::fixed(3, 3);
        assert!(fixed.check(&spectrum, &[0.1, 0.4, 1.5], 3).is_ok());
    }
}
