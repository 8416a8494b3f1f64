//! End-to-end: basis caches cannot be planted by another user. Bases are cached in the user's
//! cache folder (not a fixed name in the shared temporary folder, not next to the mesh); a
//! default cache folder is created private, and one that is a symbolic link or belongs to
//! another user is not used (a warning, and the basis is computed without it); a chosen one
//! everyone may write to is not used either; entries planted in a cache folder others can
//! write to are replaced, never followed.
#![cfg(unix)]

use crate::common::{assert_success, output_within, tvf};
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

/// Makes something at a path (a link, a FIFO, a folder…).
type Make<'a> = dyn Fn(&Path) + 'a;

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

    // A mesh file's basis goes to the same user cache folder: nothing is written next to the
    // mesh, inside the user's data set.
    let meshes = d.join("meshes");
    std::fs::create_dir(&meshes).unwrap();
    tvf_core::io::write_obj(meshes.join("ico.obj"), &tvf_core::generate::icosphere(3)).unwrap();
    std::fs::remove_dir_all(&cache).unwrap();
    let mesh = meshes.join("ico.obj").display().to_string();
    let output = coefficients(d, &[&mesh], &field);
    assert_success(&output);
    assert_eq!(entries(&meshes), 1, "tvf wrote next to the mesh");
    assert_eq!(
        entries(&cache),
        1,
        "the basis is in the user's cache folder"
    );
    let output = coefficients(d, &[&mesh], &field);
    assert!(String::from_utf8_lossy(&output.stderr).contains("using cached basis"));
}

/// The name the basis of `coefficients` (icosphere, `-k 10`) gets in a cache folder, learnt
/// from a run into a folder of its own.
fn cache_name(dir: &Path, field: &Path) -> String {
    let learn = dir.join("learn");
    let output = coefficients_in(&learn, field);
    assert_success(&output);
    let name = std::fs::read_dir(&learn).unwrap().next().unwrap().unwrap();
    name.file_name().to_string_lossy().into_owned()
}

/// `tvf coefficients --example icosphere FIELD -k 10` with `TVF_CACHE_DIR=cache`, killed (and
/// the test failed) if it takes more than a minute.
fn coefficients_in(cache: &Path, field: &Path) -> Output {
    output_within(
        tvf()
            .args(["coefficients", "--example", "icosphere"])
            .arg(field)
            .args(["-k", "10"])
            .env("TVF_CACHE_DIR", cache),
        60,
    )
}

/// A cache folder others can write to (a team's folder, group-writable here) cannot be used to
/// redirect tvf's writes or to block it: a link planted under the name of the next basis is not
/// followed (the file it points to stays as it was), a FIFO does not hang the run, a link to
/// `/dev/zero` is not "cached into"; each is replaced by the basis, and the next run reads it.
#[test]
fn planted_cache_entries_are_replaced_not_followed() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let field = d.join("f.txt");
    std::fs::write(&field, "1 0 0\n".repeat(1280)).unwrap();
    let name = cache_name(d, &field);
    let victim = d.join("victim.txt");
    std::fs::write(&victim, b"my precious file").unwrap();
    let plants: [(&str, &Make<'_>); 3] = [
        ("a link to a file of yours", &|at| {
            std::os::unix::fs::symlink(&victim, at).unwrap()
        }),
        ("a link to /dev/zero", &|at| {
            std::os::unix::fs::symlink("/dev/zero", at).unwrap()
        }),
        ("a FIFO", &|at| {
            let made = std::process::Command::new("mkfifo").arg(at).status();
            assert!(made.unwrap().success());
        }),
    ];
    for (k, (what, plant)) in plants.iter().enumerate() {
        let shared = d.join(format!("shared-{k}"));
        std::fs::create_dir(&shared).unwrap();
        std::fs::set_permissions(&shared, std::fs::Permissions::from_mode(0o770)).unwrap();
        let entry = shared.join(&name);
        plant(&entry);
        let output = coefficients_in(&shared, &field);
        assert_success(&output);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.contains("cached basis is unusable"),
            "{what}: {stderr}"
        );
        let kind = std::fs::symlink_metadata(&entry).unwrap().file_type();
        assert!(kind.is_file(), "{what}: the entry is still {kind:?}");
        let output = coefficients_in(&shared, &field);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains("using cached basis"), "{what}: {stderr}");
    }
    assert_eq!(std::fs::read(&victim).unwrap(), b"my precious file");
}

/// A chosen cache folder (`$TVF_CACHE_DIR`, `--cache-dir`) gets the checks of the default one:
/// a folder everyone may write to (0777, or 1777 as `/tmp`) is not used, with a warning, and
/// nothing is written into it.
#[test]
fn a_chosen_cache_folder_everyone_may_write_to_is_not_used() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let field = d.join("f.txt");
    std::fs::write(&field, "1 0 0\n".repeat(1280)).unwrap();
    for mode in [0o777, 0o1777] {
        let shared = d.join(format!("team-{mode:o}"));
        std::fs::create_dir(&shared).unwrap();
        std::fs::set_permissions(&shared, std::fs::Permissions::from_mode(mode)).unwrap();
        let output = coefficients_in(&shared, &field);
        assert_success(&output);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.contains("not using the basis cache") && stderr.contains("everyone may write"),
            "{stderr}"
        );
        assert_eq!(
            entries(&shared),
            0,
            "tvf wrote into a folder everyone may write to"
        );
    }
}

/// The sweep of hostile cache folders: whatever sits under the name of the next basis (a link
/// to a file of yours, to `/dev/zero`, to a folder, a loop of links, a FIFO, a folder, another
/// user's forged basis, a damaged or foreign file of yours, a hard link to a file of yours) and
/// whatever the chosen cache folder is (everyone may write to it, another user's, a file, a
/// link to a folder of yours), the run ends — killed after a minute otherwise — with the right
/// basis, exit 0 and a warning that says what it found; nothing outside the cache folder
/// changes, and a planted entry is replaced by a regular file or left alone with a warning.
/// Prints the counts.
#[test]
fn hostile_cache_folders_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let field = d.join("f.txt");
    std::fs::write(&field, "1 0 0\n".repeat(1280)).unwrap();
    let name = cache_name(d, &field);
    let good = d.join("learn").join(&name);
    let expected = coefficients_in(&d.join("learn"), &field).stdout;
    let victim = d.join("victim.txt");
    std::fs::write(&victim, b"my precious file").unwrap();
    let chown = |path: &Path| {
        std::process::Command::new("chown")
            .arg("12345")
            .arg(path)
            .status()
            .is_ok_and(|s| s.success())
    };
    let plants: Vec<(&str, Box<Make<'_>>, &str)> = vec![
        (
            "a link to a file of yours",
            Box::new(|at: &Path| std::os::unix::fs::symlink(&victim, at).unwrap()),
            "symbolic link",
        ),
        (
            "a link to /dev/zero",
            Box::new(|at: &Path| std::os::unix::fs::symlink("/dev/zero", at).unwrap()),
            "symbolic link",
        ),
        (
            "a link to a folder",
            Box::new(|at: &Path| std::os::unix::fs::symlink(d, at).unwrap()),
            "symbolic link",
        ),
        (
            "a loop of links",
            Box::new(|at: &Path| std::os::unix::fs::symlink(at, at).unwrap()),
            "symbolic link",
        ),
        (
            "a FIFO",
            Box::new(|at: &Path| {
                let made = std::process::Command::new("mkfifo").arg(at).status();
                assert!(made.unwrap().success());
            }),
            "not a regular file",
        ),
        (
            "a folder",
            Box::new(|at: &Path| std::fs::create_dir(at).unwrap()),
            "cannot cache the basis",
        ),
        (
            "a damaged basis of yours",
            Box::new(|at: &Path| {
                let bytes = std::fs::read(&good).unwrap();
                std::fs::write(at, &bytes[..bytes.len() / 2]).unwrap();
            }),
            "cached basis is unusable",
        ),
        (
            "random bytes of yours",
            Box::new(|at: &Path| std::fs::write(at, vec![0x5a; 4096]).unwrap()),
            "cached basis is unusable",
        ),
        (
            "a hard link to a file of yours",
            Box::new(|at: &Path| std::fs::hard_link(&victim, at).unwrap()),
            "cached basis is unusable",
        ),
        (
            "another user's copy of the right basis",
            Box::new(|at: &Path| {
                std::fs::copy(&good, at).unwrap();
                assert!(chown(at), "chown (the tests run as root)");
            }),
            "belongs to another user",
        ),
    ];
    let mut counts = (0, 0);
    for (k, (what, plant, said)) in plants.iter().enumerate() {
        let shared = d.join(format!("shared-{k}"));
        std::fs::create_dir(&shared).unwrap();
        std::fs::set_permissions(&shared, std::fs::Permissions::from_mode(0o770)).unwrap();
        let entry = shared.join(&name);
        plant(&entry);
        let output = coefficients_in(&shared, &field);
        assert_success(&output);
        assert_eq!(output.stdout, expected, "{what}: the coefficients");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!stderr.contains("panicked"), "{what}: {stderr}");
        assert!(
            stderr.contains("warning: ") && stderr.contains(said),
            "{what}: {stderr}"
        );
        let kind = std::fs::symlink_metadata(&entry).unwrap().file_type();
        assert!(
            kind.is_file() || *what == "a folder",
            "{what}: the entry is still {kind:?}"
        );
        counts.0 += 1;
    }
    assert_eq!(std::fs::read(&victim).unwrap(), b"my precious file");
    // Chosen folders that must not be used.
    let folders: Vec<(&str, Box<Make<'_>>, &str)> = vec![
        (
            "everyone may write to it",
            Box::new(|at: &Path| {
                std::fs::create_dir(at).unwrap();
                std::fs::set_permissions(at, std::fs::Permissions::from_mode(0o777)).unwrap();
            }),
            "everyone may write",
        ),
        (
            "a sticky folder everyone may write to",
            Box::new(|at: &Path| {
                std::fs::create_dir(at).unwrap();
                std::fs::set_permissions(at, std::fs::Permissions::from_mode(0o1777)).unwrap();
            }),
            "everyone may write",
        ),
        (
            "another user's",
            Box::new(|at: &Path| {
                std::fs::create_dir(at).unwrap();
                assert!(chown(at), "chown (the tests run as root)");
            }),
            "another user",
        ),
        (
            "a file",
            Box::new(|at: &Path| std::fs::write(at, b"x").unwrap()),
            "not a folder",
        ),
        (
            "a link to /dev/null",
            Box::new(|at: &Path| std::os::unix::fs::symlink("/dev/null", at).unwrap()),
            "not a folder",
        ),
    ];
    for (k, (what, make, said)) in folders.iter().enumerate() {
        let chosen = d.join(format!("chosen-{k}"));
        make(&chosen);
        let output = coefficients_in(&chosen, &field);
        assert_success(&output);
        assert_eq!(output.stdout, expected, "{what}: the coefficients");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.contains("not using the basis cache") && stderr.contains(said),
            "{what}: {stderr}"
        );
        if chosen.is_dir() {
            assert_eq!(entries(&chosen), 0, "{what}: written into");
        }
        counts.1 += 1;
    }
    // A chosen link to a folder of yours is your word: followed and used.
    let mine = d.join("mine");
    std::fs::create_dir(&mine).unwrap();
    std::os::unix::fs::symlink(&mine, d.join("to-mine")).unwrap();
    assert_success(&coefficients_in(&d.join("to-mine"), &field));
    assert_eq!(entries(&mine), 1);
    println!(
        "cache sweep: {} planted entries replaced or refused with a warning, {} chosen folders \
         refused with a warning, 1 chosen link followed",
        counts.0, counts.1
    );
}
