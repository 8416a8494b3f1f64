//! Injected write faults, for tests of all-or-nothing outputs and of interruption: a program
//! (the `tvf` binary reads its test variable for this) installs a hook with
//! [`inject_write_faults`], and [`super::write_atomically`] asks it about every file once the
//! content is written, before the file is put into place. The library itself never reads the
//! environment; without a hook nothing is injected.

use std::path::Path;
use std::sync::OnceLock;
use std::time::Duration;

/// What an injected fault does to the write of one file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WriteFault {
    /// The write fails as on a full disk, after the content went to the temporary file.
    Fail,
    /// The write waits there for [`STALL`], as on a very slow disk (to interrupt the process).
    Stall,
}

/// How long a [`WriteFault::Stall`] waits.
pub const STALL: Duration = Duration::from_secs(60);

/// The fault to inject into the write of a path, if any.
pub type WriteFaultHook = fn(&Path) -> Option<WriteFault>;

static HOOK: OnceLock<WriteFaultHook> = OnceLock::new();

/// Installs `hook` for the rest of the process; `false` if one was installed already (the first
/// stays).
pub fn inject_write_faults(hook: WriteFaultHook) -> bool {
    HOOK.set(hook).is_ok()
}

/// Applies the fault the hook asks for when writing `path`: an error for
/// [`WriteFault::Fail`], a wait for [`WriteFault::Stall`], nothing without a hook.
pub(crate) fn apply_injected_fault(path: &Path) -> std::io::Result<()> {
    match HOOK.get().and_then(|hook| hook(path)) {
        Some(WriteFault::Fail) => Err(std::io::Error::other("injected write failure")),
        Some(WriteFault::Stall) => {
            std::thread::sleep(STALL);
            Ok(())
        }
        None => Ok(()),
    }
}
