//! Processor time of this process and of the calling thread, for the per-phase cost of an
//! eigen computation ([`crate::PhaseStatistics`]). The standard library has no processor-time
//! clock, so these come from the platform: `getrusage` and `clock_gettime` on Unix. Elsewhere
//! the seconds are unavailable and reported as NaN (never replaced by wall-clock time, which
//! would claim one busy core): sums and ratios of them stay NaN, and a JSON report shows
//! `null`.

/// Processor seconds (user + system, every thread) of this process so far; NaN where the
/// platform has no such clock.
pub fn process_cpu_seconds() -> f64 {
    seconds_or_unavailable(platform::process_cpu_seconds())
}

/// Processor seconds of the calling thread so far; NaN where the platform has no such clock.
pub(crate) fn thread_cpu_seconds() -> f64 {
    seconds_or_unavailable(platform::thread_cpu_seconds())
}

/// Processor seconds between two readings of one clock: NaN if either is unavailable, never
/// negative otherwise (clocks of some platforms step back by a tick).
pub(crate) fn cpu_seconds_between(start: f64, end: f64) -> f64 {
    if start.is_nan() || end.is_nan() {
        f64::NAN
    } else {
        (end - start).max(0.0)
    }
}

/// A clock reading, or NaN for a platform without the clock (or a failed reading).
fn seconds_or_unavailable(reading: Option<f64>) -> f64 {
    reading.unwrap_or(f64::NAN)
}

#[cfg(unix)]
mod platform {
    /// `getrusage(RUSAGE_SELF)`: user + system time of every thread.
    pub(super) fn process_cpu_seconds() -> Option<f64> {
        // SAFETY: getrusage only writes the zero-initialised struct it is given.
        let usage = unsafe {
            let mut usage: libc::rusage = std::mem::zeroed();
            if libc::getrusage(libc::RUSAGE_SELF, &mut usage) != 0 {
                return None;
            }
            usage
        };
        let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
        Some(seconds(usage.ru_utime) + seconds(usage.ru_stime))
    }

    /// `clock_gettime(CLOCK_THREAD_CPUTIME_ID)`.
    pub(super) fn thread_cpu_seconds() -> Option<f64> {
        // SAFETY: clock_gettime only writes the zero-initialised struct it is given.
        let time = unsafe {
            let mut time: libc::timespec = std::mem::zeroed();
            if libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut time) != 0 {
                return None;
            }
            time
        };
        Some(time.tv_sec as f64 + time.tv_nsec as f64 * 1e-9)
    }
}

#[cfg(not(unix))]
mod platform {
    /// No processor-time clock in the standard library.
    pub(super) fn process_cpu_seconds() -> Option<f64> {
        None
    }

    /// No processor-time clock in the standard library.
    pub(super) fn thread_cpu_seconds() -> Option<f64> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PhaseStatistics;

    #[cfg(unix)]
    #[test]
    fn the_clocks_advance_with_work() {
        let (process, thread) = (process_cpu_seconds(), thread_cpu_seconds());
        let mut x = 0.0f64;
        for k in 0..20_000_000 {
            x += (k as f64).sqrt();
        }
        assert!(x > 0.0);
        assert!(cpu_seconds_between(process, process_cpu_seconds()) > 0.0);
        assert!(cpu_seconds_between(thread, thread_cpu_seconds()) > 0.0);
    }

    /// What a platform without the clocks reports: unavailable (NaN, `null` in JSON), never
    /// zero or the wall-clock time, through sums and the busy-core ratio.
    #[test]
    fn unavailable_clocks_are_reported_as_unavailable() {
        let unavailable = seconds_or_unavailable(None);
        assert!(unavailable.is_nan());
        assert_eq!(seconds_or_unavailable(Some(1.5)), 1.5);
        let spent = cpu_seconds_between(unavailable, unavailable);
        assert!(spent.is_nan());
        assert!(cpu_seconds_between(1.0, unavailable).is_nan());
        assert_eq!(cpu_seconds_between(2.0, 1.5), 0.0);
        let mut phase = PhaseStatistics {
            wall_seconds: 2.0,
            cpu_seconds: spent,
            ..PhaseStatistics::default()
        };
        phase += PhaseStatistics {
            wall_seconds: 1.0,
            cpu_seconds: 0.5,
            ..PhaseStatistics::default()
        };
        assert!(phase.cpu_seconds.is_nan() && phase.utilisation().is_nan());
    }
}
