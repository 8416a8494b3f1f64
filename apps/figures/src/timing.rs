//! Wall-clock timing of repeated runs: [`Repetitions`] and [`median_time`].

use std::time::Instant;

/// How often to repeat a timed operation: at most `max` times, and no more once the runs so
/// far took `budget_seconds` (always at least once).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Repetitions {
    /// Most runs.
    pub max: usize,
    /// Stop repeating once the runs so far took this many seconds.
    pub budget_seconds: f64,
}

/// The median of the measured wall-clock times (seconds) and how many runs it is over.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// Median wall-clock seconds.
    pub median: f64,
    /// Number of runs.
    pub runs: usize,
}

/// Runs `operation` as `repetitions` says and returns the median time and the last result.
pub fn median_time<T, E>(
    repetitions: Repetitions,
    mut operation: impl FnMut() -> Result<T, E>,
) -> Result<(Timing, T), E> {
    let mut times = Vec::new();
    let mut total = 0.0;
    loop {
        let start = Instant::now();
        let value = operation()?;
        let seconds = start.elapsed().as_secs_f64();
        times.push(seconds);
        total += seconds;
        if times.len() >= repetitions.max.max(1) || total >= repetitions.budget_seconds {
            return Ok((
                Timing {
                    median: median(&mut times),
                    runs: times.len(),
                },
                value,
            ));
        }
        drop(value);
    }
}

/// Median of `values` (mean of the middle two for an even count; 0 for none).
pub fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 2.0, 3.0]), 2.5);
        assert_eq!(median(&mut []), 0.0);
    }

    #[test]
    fn repetitions_stop_at_the_count_or_the_budget() {
        let mut calls = 0;
        let (timing, last) = median_time(
            Repetitions {
                max: 4,
                budget_seconds: 1e9,
            },
            || {
                calls += 1;
                Ok::<usize, ()>(calls)
            },
        )
        .unwrap();
        assert_eq!((timing.runs, last), (4, 4));
        let (timing, _) = median_time(
            Repetitions {
                max: 10,
                budget_seconds: 0.0,
            },
            || Ok::<(), ()>(()),
        )
        .unwrap();
        assert_eq!(timing.runs, 1);
    }
}
