//! Shared helpers of the CLI end-to-end tests: the `tvf` binary, the check that it succeeded,
//! a quiet run and its JSON, and test field and constraint files.

use std::path::Path;
use std::process::{Command, Output};
use tvf_core::TriangleMesh;

/// A command running the `tvf` binary built for these tests, with the user's cache folder
/// (the default basis cache) in the tests' temporary folder rather than the home folder.
pub fn tvf() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_tvf"));
    command.env(
        "XDG_CACHE_HOME",
        Path::new(env!("CARGO_TARGET_TMPDIR")).join("xdg-cache"),
    );
    command
}

/// Fails the test (at the caller's line) with the command's stderr unless it exited with 0.
#[track_caller]
pub fn assert_success(output: &Output) {
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Runs `tvf ARGS --quiet` in `dir` and fails the test unless it succeeded.
#[track_caller]
pub fn run_quiet(dir: &Path, args: &[&str]) -> Output {
    let output = tvf()
        .current_dir(dir)
        .args(args)
        .arg("--quiet")
        .output()
        .expect("the tvf binary runs");
    assert_success(&output);
    output
}

/// The JSON a command printed on stdout.
pub fn stdout_json(output: &Output) -> serde_json::Value {
    serde_json::from_slice(&output.stdout).expect("JSON on stdout")
}

/// Writes `field.txt` (a rotation about z plus a gradient-like part, one vector per face) and
/// `c.json` (a vector at face 12, a divergence at vertex 5, a curl at face 40) into `dir`: the
/// inputs of the every-command tests.
pub fn write_field_and_constraints(mesh: &TriangleMesh, dir: &Path) {
    let field: String = mesh
        .faces()
        .iter()
        .map(|f| {
            let c: [f64; 3] = std::array::from_fn(|k| {
                f.iter().map(|&v| mesh.positions()[v][k]).sum::<f64>() / 3.0
            });
            format!("{} {} {}\n", -c[1] + 0.3 * c[2], c[0], -0.3 * c[0])
        })
        .collect();
    std::fs::write(dir.join("field.txt"), field).unwrap();
    let constraints = r#"{"constraints": [
        {"id": "v", "kind": "vector", "face": 12, "value": [1.0, 0.0, 0.0]},
        {"id": "s", "kind": "divergence", "vertex": 5, "value": 2.0},
        {"id": "c", "kind": "curl", "face": 40, "value": -1.0}
    ]}"#;
    std::fs::write(dir.join("c.json"), constraints).unwrap();
}

/// Writes a field with both families (a rotation about z plus a gradient-like part, one vector
/// per face, as text) to `path`.
pub fn write_field(mesh: &TriangleMesh, path: &Path) {
    let field: String = mesh
        .faces()
        .iter()
        .map(|f| {
            let c: [f64; 3] = std::array::from_fn(|k| {
                f.iter().map(|&v| mesh.positions()[v][k]).sum::<f64>() / 3.0
            });
            format!("{} {} {}\n", -c[1] + 0.3 * c[0], c[0] + 0.2, 0.1 * c[2])
        })
        .collect();
    std::fs::write(path, field).unwrap();
}

/// Runs `command` to its end, or kills it after `seconds` and fails the test saying it hung
/// (stdin closed, stdout and stderr captured).
#[track_caller]
pub fn output_within(command: &mut Command, seconds: u64) -> Output {
    use std::process::Stdio;
    let mut child = command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the command starts");
    // Read both pipes while waiting, so a chatty child cannot block on a full pipe.
    let mut stdout = child.stdout.take().expect("piped");
    let mut stderr = child.stderr.take().expect("piped");
    let out = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut stdout, &mut bytes).map(|_| bytes)
    });
    let err = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut stderr, &mut bytes).map(|_| bytes)
    });
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("the child can be waited for") {
            break status;
        }
        if start.elapsed() > std::time::Duration::from_secs(seconds) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{command:?} hung: killed after {seconds} s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    Output {
        status,
        stdout: out.join().expect("reader").unwrap_or_default(),
        stderr: err.join().expect("reader").unwrap_or_default(),
    }
}

/// [`output_within`], also returning the peak resident memory of the process in KiB (from
/// `wait4`'s resource usage). The child is forked (not spawned sharing this process's memory,
/// whose own peak would then count as the child's): its count starts from this process's
/// current size, so a small test process measures the child.
#[cfg(unix)]
#[track_caller]
// The child is reaped by `wait4` (which also gives its resource usage), not `Child::wait`.
#[allow(clippy::zombie_processes)]
pub fn output_and_peak_memory_within(command: &mut Command, seconds: u64) -> (Output, u64) {
    use std::os::unix::process::{CommandExt, ExitStatusExt};
    use std::process::Stdio;
    // SAFETY: the hook does nothing; having one makes std fork and exec instead of posix_spawn.
    unsafe {
        command.pre_exec(|| Ok(()));
    }
    let mut child = command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the command starts");
    let mut stdout = child.stdout.take().expect("piped");
    let mut stderr = child.stderr.take().expect("piped");
    let out = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut stdout, &mut bytes).map(|_| bytes)
    });
    let err = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(&mut stderr, &mut bytes).map(|_| bytes)
    });
    let pid = child.id() as libc::pid_t;
    let start = std::time::Instant::now();
    let (status, usage) = loop {
        let mut status = 0;
        // SAFETY: an all-zero rusage is valid, and wait4 writes it for our own child.
        let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
        // SAFETY: waits for our own child without blocking; both pointers are valid.
        let reaped = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
        if reaped == pid {
            break (status, usage);
        }
        assert!(reaped == 0, "wait4: {}", std::io::Error::last_os_error());
        if start.elapsed() > std::time::Duration::from_secs(seconds) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{command:?} hung: killed after {seconds} s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    let output = Output {
        status: std::process::ExitStatus::from_raw(status),
        stdout: out.join().expect("reader").unwrap_or_default(),
        stderr: err.join().expect("reader").unwrap_or_default(),
    };
    // ru_maxrss is in KiB on Linux.
    (output, usage.ru_maxrss.max(0) as u64)
}
