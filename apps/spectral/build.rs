//! Build script: names the platforms whose `sysconf` tells the physical memory
//! (`cfg(sysconf_memory)`, used by `src/dense_memory.rs`).

use cfg_aliases::cfg_aliases;

fn main() {
    cfg_aliases! {
        sysconf_memory: {
            any(
                target_os = "linux",
                target_os = "android",
                target_os = "macos",
                target_os = "ios",
                target_os = "freebsd",
                target_os = "openbsd",
                target_os = "netbsd",
                target_os = "dragonfly",
                target_os = "illumos",
                target_os = "solaris"
            )
        },
    }
}
