//! Clean interruption: Ctrl+C, and on Unix SIGINT, SIGTERM and SIGHUP, delete the temporary
//! files and folders this process is writing ([`tvf_core::io::temporaries`]; after a commit of
//! outputs in progress, so outputs appear together or not at all) before it exits with
//! `128 + signal`, so an interrupted `tvf basis … -o D/x.tvfb` leaves neither a partial output
//! nor a temporary in `D`.
//!
//! On Unix the signals are taken by `signal-hook`, whose handler only wakes a thread of its own,
//! where cleaning up is safe (no async-signal restrictions). Elsewhere `ctrlc` runs the clean-up
//! on its own thread for the console's interrupt and close events, and tvf exits with 130 (as
//! for SIGINT), since those events have no signal number. Both call [`clean_up_and_exit`].

use std::sync::atomic::{AtomicBool, Ordering};

/// Set when an interruption has been taken: the process is cleaning up and about to exit.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Installs the clean-up; call first in `main`, before any other thread starts. If it cannot be
/// installed, the default actions stay.
pub fn install() {
    #[cfg(unix)]
    unix_signals::install();
    #[cfg(not(unix))]
    console_events::install();
}

/// Removes the temporaries (once a commit in progress has ended) and exits with
/// `128 + signal`.
fn clean_up_and_exit(signal: i32) -> ! {
    INTERRUPTED.store(true, Ordering::SeqCst);
    tvf_core::io::temporaries::remove_temporaries();
    std::process::exit(128 + signal)
}

/// Unix: SIGINT, SIGTERM and SIGHUP through `signal-hook`.
#[cfg(unix)]
mod unix_signals {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    use signal_hook::iterator::Signals;

    /// Starts the thread that registers the signals and takes them (without the thread, or if
    /// they cannot be registered, their default actions stay).
    pub fn install() {
        let _ = std::thread::Builder::new()
            .name("tvf-signals".into())
            .spawn(|| {
                let Ok(mut signals) = Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
                    return;
                };
                if let Some(signal) = signals.forever().next() {
                    super::clean_up_and_exit(signal);
                }
            });
    }
}

/// Everywhere: the console's interrupt and close events through `ctrlc` (used off Unix, and
/// tested on Unix too).
#[cfg(any(not(unix), test))]
mod console_events {
    /// The signal number of an interrupt (SIGINT on every Unix); its exit code is 130.
    const INTERRUPT_SIGNAL: i32 = 2;

    /// Sets the handler; `false` if one could not be set.
    pub fn install() -> bool {
        ctrlc::set_handler(|| super::clean_up_and_exit(INTERRUPT_SIGNAL)).is_ok()
    }
}

/// A report piped into a reader that stops early (`tvf info mesh.obj | head -c 100`) ends tvf
/// quietly with SIGPIPE, as it ends other Unix tools: Rust ignores SIGPIPE, so the write would
/// fail and `println!` panic. Not for the editor's server, whose sockets must survive a
/// client that goes away (tvf's output files are never pipes, so no temporary is left behind).
/// Elsewhere there is no SIGPIPE: nothing to change.
pub fn end_quietly_on_closed_pipe() {
    #[cfg(unix)]
    // SAFETY: restoring the default action of one signal; no handler is involved.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// Waits for the exit of the interruption in progress, if any: the main thread calls it before
/// it ends the process itself, so that an interrupted run exits with `128 + signal` (not with
/// the error its removed temporaries caused, nor with success).
pub fn yield_to_interruption() {
    while INTERRUPTED.load(Ordering::SeqCst) {
        std::thread::park_timeout(std::time::Duration::from_secs(1));
    }
}

#[cfg(test)]
mod tests {
    /// Set in the child process of [`the_console_handler_cleans_up_and_exits_130`]: the
    /// temporary file it registers.
    const CHILD_VARIABLE: &str = "TVF_INTERRUPT_TEST_CHILD";

    /// The portable handler (`ctrlc`, the one used off Unix), run in a child process of this
    /// test binary: an interrupt removes the registered temporary and exits with 130.
    #[cfg(unix)]
    #[test]
    fn the_console_handler_cleans_up_and_exits_130() {
        if let Some(temporary) = std::env::var_os(CHILD_VARIABLE) {
            assert!(super::console_events::install());
            let temporary = std::path::PathBuf::from(temporary);
            // Written by the parent: registered as it is.
            let ((), _registration) =
                tvf_core::io::temporaries::create_registered(|| Ok(()), |()| temporary.clone())
                    .unwrap();
            // SAFETY: sending SIGINT to this very process, whose handler was just set.
            unsafe {
                libc::kill(libc::getpid(), libc::SIGINT);
            }
            std::thread::sleep(std::time::Duration::from_secs(30));
            panic!("the interrupt did not end the process");
        }
        let dir = tempfile::tempdir().unwrap();
        let temporary = dir.path().join(".tvf-write-interrupted.tmp");
        std::fs::write(&temporary, b"partial").unwrap();
        let status = std::process::Command::new(std::env::current_exe().unwrap())
            .args([
                "interrupt::tests::the_console_handler_cleans_up_and_exits_130",
                "--exact",
                "--nocapture",
            ])
            .env(CHILD_VARIABLE, &temporary)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .status()
            .unwrap();
        assert_eq!(status.code(), Some(130));
        assert!(!temporary.exists(), "the temporary was not removed");
    }
}
