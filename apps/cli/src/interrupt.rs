//! Clean interruption: SIGINT, SIGTERM and SIGHUP delete the temporary files and folders this
//! process is writing ([`tvf_core::io::temporaries`]) before it exits with `128 + signal`, so an
//! interrupted `tvf basis … -o D/x.tvfb` leaves neither a partial output nor a temporary in `D`.
//!
//! The signals are blocked in every thread and taken by one thread with `sigwait`, where
//! cleaning up is safe (no async-signal restrictions).

use std::sync::atomic::{AtomicBool, Ordering};

/// Set when a signal has been taken: the process is cleaning up and about to exit.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// The signals that end tvf after cleaning up.
const SIGNALS: [libc::c_int; 3] = [libc::SIGINT, libc::SIGTERM, libc::SIGHUP];

/// Installs the clean-up; call first in `main`, before any other thread starts (threads inherit
/// the blocked signals). Without it (if the signals cannot be blocked) the defaults stay.
pub fn install() {
    // SAFETY: `sigset_t` is plain data that sigemptyset initialises; the calls only read and
    // write the local set and the calling thread's signal mask.
    let set = unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for signal in SIGNALS {
            libc::sigaddset(&mut set, signal);
        }
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return;
        }
        set
    };
    let waiter = std::thread::Builder::new()
        .name("tvf-signals".into())
        .spawn(move || loop {
            let mut signal: libc::c_int = 0;
            // SAFETY: `set` is an initialised signal set and `signal` a valid out-pointer.
            if unsafe { libc::sigwait(&set, &mut signal) } == 0 {
                INTERRUPTED.store(true, Ordering::SeqCst);
                tvf_core::io::temporaries::remove_temporaries();
                std::process::exit(128 + signal);
            }
        });
    if waiter.is_err() {
        // No thread to take the signals: restore their default action.
        // SAFETY: as above.
        unsafe {
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
        }
    }
}

/// A report piped into a reader that stops early (`tvf info mesh.obj | head -c 100`) ends tvf
/// quietly with SIGPIPE, as it ends other Unix tools: Rust ignores SIGPIPE, so the write would
/// fail and `println!` panic. Not for the editor's server, whose sockets must survive a
/// client that goes away (tvf's output files are never pipes, so no temporary is left behind).
pub fn end_quietly_on_closed_pipe() {
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
