//! Progress of the passes over a basis file read in blocks (`--basis FILE` of `filter`,
//! `coefficients`, `compress`, `decompress`, `rate-distortion`, `spline`, `design --reduced`;
//! of `edit`, the check at opening only), shown as other long work is ([`Progress`]: a bar on a
//! terminal, plain lines when stderr is redirected, nothing with `--quiet`): one task `basis
//! file` per pass of more than one block (the check at opening, a projection, a synthesis, the
//! fields of the basis id, the rows of `U`), in KiB of the file, or MiB for passes of 64 MiB or
//! more. Passes made on worker threads, several at once (`compress` projects its frames in
//! parallel, each with a pass of its own), are not shown: the frames' own progress is.

use crate::progress::{is_quiet, Progress};
use std::sync::{Arc, Mutex};
use tvf_spectral::{BlockObserver, BlockProgress};

/// Passes of at least this many bytes are counted in MiB, smaller ones in KiB.
const MIB_PASS: u64 = 64 << 20;

/// The observer of a basis file read in blocks that shows the progress of its passes on
/// stderr; `None` with `--quiet`.
pub fn basis_file_observer() -> Option<BlockObserver> {
    if is_quiet() {
        return None;
    }
    let shown: Mutex<Option<Progress>> = Mutex::new(None);
    Some(Arc::new(move |p: BlockProgress| {
        if rayon::current_thread_index().is_some() {
            return;
        }
        let Ok(mut shown) = shown.lock() else { return };
        if p.done_bytes == 0 {
            // A new pass: shown once its first block is read, if there are more to read.
            *shown = None;
            return;
        }
        let (unit, bytes) = if p.total_bytes >= MIB_PASS {
            ("MiB", 1 << 20)
        } else {
            ("KiB", 1 << 10)
        };
        let in_units = |b: u64| usize::try_from(b.div_ceil(bytes)).unwrap_or(usize::MAX);
        let stage = format!("{}, {unit}", p.pass.name());
        if p.done_bytes < p.total_bytes && shown.is_none() {
            *shown = Some(Progress::new("basis file"));
        }
        if let Some(progress) = shown.as_ref() {
            progress.update(&stage, in_units(p.done_bytes), in_units(p.total_bytes));
        }
        if p.done_bytes == p.total_bytes {
            // The pass is over: its bar is cleared.
            *shown = None;
        }
    }))
}
