//! [`check_dense_memory`]: whether the machine has the memory a dense eigensolve of every
//! eigenpair (the complete basis) needs, checked before it starts, so that `-k 1000000000000`
//! on a large mesh is refused with the sizes instead of exhausting the machine.

use crate::BasisError;

/// Bytes a dense solve of both scalar eigenproblems (`a` and `b` unknowns) and the dense
/// `(a + b)`-column field matrix take at least: three `n × n` matrices per eigenproblem (the
/// matrix, its eigenvectors, the workspace) and the fields, in `f64`.
pub fn dense_solve_bytes(a: usize, b: usize) -> f64 {
    let (a, b) = (a as f64, b as f64);
    8.0 * (3.0 * (a * a + b * b) + (a + b) * (a + b))
}

/// The memory available for a new allocation (`MemAvailable` of `/proc/meminfo`), bytes;
/// `None` where that cannot be read.
pub fn available_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024.0)
}

/// Refuses a dense solve of `a` and `b` unknowns that needs more memory than is available
/// (see [`dense_solve_bytes`]); the message gives both sizes.
pub fn check_dense_memory(a: usize, b: usize) -> Result<(), BasisError> {
    let needed = dense_solve_bytes(a, b);
    match available_memory() {
        Some(available) if needed > available => Err(BasisError::InvalidRequest(format!(
            "the complete basis needs dense eigensolves of {a} and {b} unknowns: at least \
                 {:.1} GiB of memory, but only {:.1} GiB are available (ask for fewer fields, \
                 e.g. -k 1000)",
            needed / GIB,
            available / GIB
        ))),
        _ => Ok(()),
    }
}

const GIB: f64 = (1u64 << 30) as f64;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_solves_pass_and_huge_ones_are_refused_with_their_size() {
        assert!(check_dense_memory(100, 300).is_ok());
        if available_memory().is_some() {
            let error = check_dense_memory(10_000_000, 30_000_000).unwrap_err();
            let text = error.to_string();
            assert!(text.contains("GiB") && text.contains("30000000"), "{text}");
        }
    }
}
