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

/// The memory available for a new allocation, bytes: `MemAvailable` of `/proc/meminfo` on
/// Linux, the physical memory on other systems that tell it (`sysconf`), `None` elsewhere.
pub fn available_memory() -> Option<f64> {
    #[cfg(target_os = "linux")]
    return meminfo_available(&std::fs::read_to_string("/proc/meminfo").ok()?);
    #[cfg(all(sysconf_memory, not(target_os = "linux")))]
    return physical_memory();
    #[cfg(not(sysconf_memory))]
    return None;
}

/// `MemAvailable` of the text of `/proc/meminfo`, bytes.
#[cfg_attr(not(target_os = "linux"), allow(dead_code))]
fn meminfo_available(meminfo: &str) -> Option<f64> {
    let line = meminfo.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024.0)
}

/// The physical memory (`sysconf` pages × page size), bytes: an upper bound of what is
/// available, on systems without `/proc/meminfo`.
#[cfg(sysconf_memory)]
#[cfg_attr(target_os = "linux", allow(dead_code))]
fn physical_memory() -> Option<f64> {
    // SAFETY: sysconf only reads system constants.
    let (pages, page_size) = unsafe {
        (
            libc::sysconf(libc::_SC_PHYS_PAGES),
            libc::sysconf(libc::_SC_PAGESIZE),
        )
    };
    (pages > 0 && page_size > 0).then_some(pages as f64 * page_size as f64)
}

/// The most a dense solve may take where the system does not tell its memory.
pub const UNMEASURED_MEMORY_LIMIT: f64 = 16.0 * GIB;

/// Refuses a dense solve of `a` and `b` unknowns that needs more memory than is available
/// (see [`dense_solve_bytes`]), or, where the system does not tell, more than
/// [`UNMEASURED_MEMORY_LIMIT`]; the message gives both sizes.
pub fn check_dense_memory(a: usize, b: usize) -> Result<(), BasisError> {
    check_against(a, b, available_memory())
}

/// [`check_dense_memory`] with the available memory given (`None`: unknown).
fn check_against(a: usize, b: usize, available: Option<f64>) -> Result<(), BasisError> {
    let needed = dense_solve_bytes(a, b);
    let refuse = |limit: String| {
        Err(BasisError::InvalidRequest(format!(
            "the complete basis needs dense eigensolves of {a} and {b} unknowns: at least \
             {:.1} GiB of memory, but {limit} (ask for fewer fields, e.g. -k 1000)",
            needed / GIB
        )))
    };
    match available {
        Some(available) if needed > available => {
            refuse(format!("only {:.1} GiB are available", available / GIB))
        }
        None if needed > UNMEASURED_MEMORY_LIMIT => refuse(format!(
            "this system does not tell how much memory is available, and without that tvf \
             allows at most {:.1} GiB",
            UNMEASURED_MEMORY_LIMIT / GIB
        )),
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

    /// The fallbacks, whichever this platform uses: without a figure the fixed limit applies,
    /// and the `/proc/meminfo` and `sysconf` readings agree with each other.
    #[test]
    fn every_source_of_the_figure_works() {
        assert!(check_against(100, 300, None).is_ok());
        let text = check_against(100_000, 100_000, None)
            .unwrap_err()
            .to_string();
        assert!(
            text.contains("does not tell") && text.contains("16.0 GiB"),
            "{text}"
        );
        let meminfo = "MemTotal:       16000000 kB\nMemAvailable:    8000000 kB\n";
        assert_eq!(meminfo_available(meminfo), Some(8_192_000_000.0));
        assert_eq!(meminfo_available("MemTotal: 1 kB\n"), None);
        #[cfg(target_os = "linux")]
        {
            let physical = physical_memory().unwrap();
            assert!(physical >= available_memory().unwrap(), "{physical}");
        }
    }
}
