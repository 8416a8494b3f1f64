//! The [`BlockObserver`] of a `tvf.BasisFile` product: each block of a pass over the file is
//! reported to the optional Python callable `progress(stage, done, wanted)` (the pass's name,
//! bytes done and bytes in all, see [`tvf_spectral::BlockProgress`]) and is where Ctrl+C is
//! noticed ([`Interruption::poll`]): a `KeyboardInterrupt` — or whatever the callable raises —
//! stops the pass at once and is raised when it has unwound ([`crate::interrupt::interruptible`]
//! with the same [`Interruption`]).

use crate::interrupt::Interruption;
use crate::progress::report_progress;
use pyo3::prelude::*;
use std::sync::Arc;
use tvf_spectral::{BlockObserver, BlockProgress};

/// The observer reporting to `callback` (`None`: Ctrl+C polled only) and stopping through
/// `interruption`.
pub fn block_observer(
    callback: Option<Py<PyAny>>,
    interruption: Arc<Interruption>,
) -> BlockObserver {
    Arc::new(move |p: BlockProgress| {
        report_progress(
            callback.as_ref(),
            &interruption,
            p.pass.name(),
            p.done_bytes,
            p.total_bytes,
        )
    })
}
