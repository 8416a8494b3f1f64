//! End-to-end: the default basis caches cannot be planted by another user. Built-in examples
//! are cached in the user's cache folder (not a fixed name in the shared temporary folder); a
//! default cache folder is created private, and one that is a symbolic link or belongs to
//! another user is not used (a warning, and the basis is computed without it).
#![cfg(unix)]

use crate::common::{assert_success, tvf};
use std::os::unix::fs::PermissionsExt;
use std::path::Path;
use std::process::Output;

/// `tvf coefficients` on the icosphere with `field`, with `HOME` and `TMPDIR` in `dir` and no
/// cache variables, so only the default cache folders are in play.
fn coefficients(dir: &Path, mesh: &[&str], field: &Path) -> Output {
    tvf()
        .args(["coefficients"])
        .args(mesh)
        .arg(field)
        .args(["-k", "10"])
        .env("HOME", dir.join("home"))
        .env("TMPDIR", dir.join("tmp"))
        .env_remove("XDG_CACHE_HOME")
        .env_remove("TVF_CACHE_DIR")
        .output()
        .expect("the tvf binary runs")
}

fn entries(folder: &Path) -> usize {
    std::fs::read_dir(folder).map_or(0, |e| e.count())
}

#[test]
fn planted_links_are_not_followed_and_the_cache_is_private() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for folder in ["home/.cache", "tmp", "victim"] {
        std::fs::create_dir_all(d.join(folder)).unwrap();
    }
    let field = d.join("f.txt");
    std::fs::write(&field, "1 0 0\n".repeat(1280)).unwrap();
    let victim = d.join("victim");
    // Links where tvf keeps (or kept) the cache of examples, planted by someone else.
    std::os::unix::fs::symlink(&victim, d.join("tmp/tvf-cache")).unwrap();
    std::os::unix::fs::symlink(&victim, d.join("home/.cache/tvf")).unwrap();
    let example = ["--example", "icosphere"];
    let output = coefficients(d, &example, &field);
    assert_success(&output);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("not using the basis cache") && stderr.contains("symbolic link"),
        "{stderr}"
    );
    assert_eq!(entries(&victim), 0, "tvf wrote through a planted link");

    // Without the link, the cache folder is created private and used.
    std::fs::remove_file(d.join("home/.cache/tvf")).unwrap();
    assert_success(&coefficients(d, &example, &field));
    let cache = d.join("home/.cache/tvf");
    let mode = std::fs::metadata(&cache).unwrap().permissions().mode();
    assert_eq!(mode & 0o777, 0o700, "{mode:o}");
    assert_eq!(entries(&cache), 1, "one cached basis");
    let output = coefficients(d, &example, &field);
    assert!(String::from_utf8_lossy(&output.stderr).contains("using cached basis"));
    assert_eq!(entries(&victim), 0);

    // A folder of another user (made here by chown, as root) is not used either.
    let chowned = std::process::Command::new("chown")
        .args(["12345"])
        .arg(&cache)
        .status()
        .is_ok_and(|s| s.success());
    if chowned {
        let output = coefficients(d, &example, &field);
        assert_success(&output);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains("another user"), "{stderr}");
        assert!(!stderr.contains("using cached basis"), "{stderr}");
    }

    // Next to a mesh file: the same checks for its .tvf-cache.
    let meshes = d.join("meshes");
    std::fs::create_dir(&meshes).unwrap();
    tvf_core::io::write_obj(meshes.join("ico.obj"), &tvf_core::generate::icosphere(3)).unwrap();
    std::os::unix::fs::symlink(&victim, meshes.join(".tvf-cache")).unwrap();
    let mesh = meshes.join("ico.obj").display().to_string();
    let output = coefficients(d, &[&mesh], &field);
    assert_success(&output);
    assert!(String::from_utf8_lossy(&output.stderr).contains("symbolic link"));
    assert_eq!(entries(&victim), 0, "tvf wrote through a planted link");
}
