//! [`ResidentPeak`]: the most physical memory a stretch of work held, for `tvf compare`'s
//! `peak_bytes`. The process's high-water mark (`VmHWM`) covers the whole run, not one entry,
//! so it is reset first: on Linux, writing `5` to `/proc/self/clear_refs` sets `VmHWM` back to
//! the current resident size (`VmRSS`). The measure is `VmHWM − VmRSS at the start`: the
//! resident memory the work added at its peak, above what the process held when it began
//! (memory the allocator kept from earlier work and reused counts as already resident, so it
//! is a lower bound of what the work allocated). Elsewhere there is no measure (`None`).

/// A started measurement; see the [module](self).
#[derive(Debug, Clone, Copy)]
pub struct ResidentPeak {
    start_resident: u64,
}

impl ResidentPeak {
    /// Resets the high-water mark and notes the resident size; `None` where either is not
    /// possible (not Linux, or `/proc` not mounted or not writable).
    pub fn start() -> Option<Self> {
        std::fs::write("/proc/self/clear_refs", "5").ok()?;
        let start_resident = status_bytes("VmRSS:")?;
        Some(Self { start_resident })
    }

    /// The resident bytes added at the peak since [`ResidentPeak::start`] (0 if the resident
    /// size never grew above where it started).
    pub fn added_bytes(&self) -> Option<u64> {
        let peak = status_bytes("VmHWM:")?;
        Some(peak.saturating_sub(self.start_resident))
    }
}

/// The value of the line starting with `key` of `/proc/self/status` (given in kB), in bytes.
fn status_bytes(key: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(key))?;
    let kilobytes: u64 = line[key.len()..]
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kilobytes * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[cfg(target_os = "linux")]
    fn memory_resident_before_the_start_is_not_counted_and_memory_touched_after_is() {
        let before = vec![1u8; 64 << 20];
        std::hint::black_box(&before);
        let peak = ResidentPeak::start().expect("Linux offers clear_refs and VmHWM");
        let small = peak.added_bytes().unwrap();
        assert!(small < 32 << 20, "{small}");
        let during = vec![1u8; 96 << 20];
        std::hint::black_box(&during);
        drop(during);
        let added = peak.added_bytes().unwrap();
        assert!(added >= 90 << 20, "{added}");
        drop(before);
    }
}
