//! Timings of the benchmark examples in processes of their own: each measurement runs this
//! executable again with an internal flag (so no run inherits another's memory, page cache
//! state or thread pool), the child prints its times on one line, and the parent reports
//! medians over the runs and the machine's load before and after.

use std::process::Command;

/// What a child prints before its times.
const TIMING_TAG: &str = "bench-timing";

/// Wall-clock and processor seconds (all threads) of one measurement.
#[derive(Debug, Clone, Copy)]
pub struct Timing {
    pub wall: f64,
    pub cpu: f64,
}

/// Prints `timing` for the parent (the last line of a child's output).
pub fn report_child(timing: Timing) {
    println!("{TIMING_TAG} {} {}", timing.wall, timing.cpu);
}

/// Runs this executable with `args` and returns the timing it printed and the rest of its output.
pub fn run_child(args: &[String]) -> Result<(Timing, String), String> {
    let exe = std::env::current_exe().map_err(|e| format!("this executable: {e}"))?;
    let output = Command::new(exe)
        .args(args)
        .output()
        .map_err(|e| format!("running {args:?}: {e}"))?;
    if !output.status.success() {
        return Err(format!(
            "{args:?} failed: {}",
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let mut rest = String::new();
    let mut timing = None;
    for line in stdout.lines() {
        match line.strip_prefix(TIMING_TAG) {
            Some(values) => {
                let v: Vec<f64> = values
                    .split_whitespace()
                    .filter_map(|s| s.parse().ok())
                    .collect();
                if let [wall, cpu] = v[..] {
                    timing = Some(Timing { wall, cpu });
                }
            }
            None => {
                rest.push_str(line);
                rest.push('\n');
            }
        }
    }
    timing
        .map(|t| (t, rest))
        .ok_or_else(|| format!("{args:?} printed no timing"))
}

/// The median of `values` (the mean of the middle two for an even count; NaN if empty).
pub fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => sorted[n / 2],
        _ => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    }
}

/// The smallest and largest of `values`.
pub fn range(values: &[f64]) -> (f64, f64) {
    values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
}

/// The one-minute load average (`/proc/loadavg`), or "?" where it cannot be read.
pub fn load() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_owned))
        .unwrap_or_else(|| "?".into())
}
