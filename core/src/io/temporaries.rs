//! The temporary files and folders tvf writes next to its outputs before renaming them into
//! place (`.tvf-write-*.tmp` files, `.tvf-folder-*.tmp` folders): a registry of those this
//! process is writing, which [`remove_temporaries`] deletes when the process is interrupted
//! (SIGINT, SIGTERM), and [`sweep_stale_temporaries`], which deletes the ones a killed process
//! left behind.
//!
//! A temporary is created and registered in one step ([`create_registered`]) that the removal
//! waits for, so an interruption never finds one created but not yet registered; once the
//! removal has begun, no new temporary is created. The process's other threads go on writing
//! until it exits, so a folder that gains a file while it is being emptied is emptied again.
//!
//! Putting finished outputs into place (the renames of [`super::write_atomically`],
//! [`super::StagedFolder::commit`], [`super::StagedFile::commit`]) runs inside
//! [`commit_uninterrupted`], and [`remove_temporaries`] waits for it: an interruption never
//! lands between the renames of one command's outputs, which so appear together or not at all.

use std::cell::Cell;
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant, SystemTime};

/// Name prefix of a temporary output file.
pub const TEMPORARY_FILE_PREFIX: &str = ".tvf-write-";
/// Name prefix of a temporary output folder.
pub const TEMPORARY_FOLDER_PREFIX: &str = ".tvf-folder-";
/// Name suffix of both.
pub const TEMPORARY_SUFFIX: &str = ".tmp";
/// A temporary not modified for this long belongs to no running process (a running write
/// touches its file at least every few seconds) and is swept.
pub const STALE_AFTER: Duration = Duration::from_secs(3600);

/// How long [`remove_temporaries`] goes on emptying a folder that the process's other threads
/// keep writing into (each pass takes microseconds; the writers stop at their next new file).
const FOLDER_REMOVAL_PATIENCE: Duration = Duration::from_secs(2);

/// Temporaries this process is writing.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
/// Set (under the [`LIVE`] lock) once [`remove_temporaries`] has begun: the process is about to
/// exit and [`create_registered`] creates nothing more.
static CLOSED: AtomicBool = AtomicBool::new(false);
/// Held while finished outputs are put into place; see [`commit_uninterrupted`].
static COMMITTING: Mutex<()> = Mutex::new(());
thread_local! {
    /// Whether this thread holds [`COMMITTING`].
    static COMMITTING_HERE: Cell<bool> = const { Cell::new(false) };
}
/// Folders already swept by this process.
static SWEPT: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);

/// A temporary in [the registry](self); leaves it when dropped (after a rename or a removal).
#[derive(Debug)]
pub struct Registration(PathBuf);

impl Drop for Registration {
    fn drop(&mut self) {
        let mut live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(k) = live.iter().position(|p| *p == self.0) {
            live.swap_remove(k);
        }
    }
}

/// Creates a temporary file or folder with `create` and registers the path `path_of` gives
/// it, until the returned guard is dropped. [`remove_temporaries`] waits for the two steps, so it
/// removes the new temporary with the others; once it has begun, nothing is created and the
/// error is [`std::io::ErrorKind::Interrupted`]. `create` must not block on anything but the
/// file system, nor create another temporary.
pub fn create_registered<T>(
    create: impl FnOnce() -> std::io::Result<T>,
    path_of: impl FnOnce(&T) -> PathBuf,
) -> std::io::Result<(T, Registration)> {
    let mut live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
    if CLOSED.load(Ordering::SeqCst) {
        return Err(std::io::Error::new(
            std::io::ErrorKind::Interrupted,
            "tvf was interrupted and is removing its temporary files",
        ));
    }
    let temporary = create()?;
    let path = path_of(&temporary);
    live.push(path.clone());
    Ok((temporary, Registration(path)))
}

/// Deletes every registered temporary (for a signal handler: the process exits next), after
/// the [`commit_uninterrupted`] in progress, if any, has ended, and stops the creation of new
/// ones. Returns how many were deleted.
pub fn remove_temporaries() -> usize {
    let _committing = COMMITTING.lock().unwrap_or_else(|e| e.into_inner());
    let live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
    CLOSED.store(true, Ordering::SeqCst);
    remove_listed(&live, |_| true)
}

/// Runs `commit`, which puts finished outputs into place (renames), so that
/// [`remove_temporaries`] waits until it has ended: outputs committed together appear together
/// even when the process is interrupted meanwhile. `commit` must not block on anything but the
/// file system (renames, removals).
/// A commit nested in another (a folder committed among a command's outputs) runs in the
/// section its caller holds.
pub fn commit_uninterrupted<T>(commit: impl FnOnce() -> T) -> T {
    if COMMITTING_HERE.with(Cell::get) {
        return commit();
    }
    let _committing = COMMITTING.lock().unwrap_or_else(|e| e.into_inner());
    /// Marks this thread as committing until dropped (also when `commit` panics).
    struct Here;
    impl Drop for Here {
        fn drop(&mut self) {
            COMMITTING_HERE.with(|here| here.set(false));
        }
    }
    COMMITTING_HERE.with(|here| here.set(true));
    let _here = Here;
    commit()
}

/// Deletes the registered temporaries for which `selected` holds, once no commit is in
/// progress, without stopping the creation of new ones; returns how many. (The tests' own
/// [`remove_temporaries`]: tests running at the same time keep their temporaries.)
#[cfg(test)]
fn remove_registered(selected: impl Fn(&Path) -> bool) -> usize {
    let _committing = COMMITTING.lock().unwrap_or_else(|e| e.into_inner());
    let live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
    remove_listed(&live, selected)
}

/// Deletes the temporaries in `live` for which `selected` holds; returns how many.
fn remove_listed(live: &[PathBuf], selected: impl Fn(&Path) -> bool) -> usize {
    live.iter()
        .filter(|path| selected(path))
        .filter(|path| {
            if path.is_dir() {
                remove_folder(path)
            } else {
                std::fs::remove_file(path).is_ok()
            }
        })
        .count()
}

/// Removes the folder `path` with its content, again while another thread's write into it
/// (a file created or renamed there after the listing) makes the final removal fail, for at
/// most [`FOLDER_REMOVAL_PATIENCE`]. Whether it was removed.
fn remove_folder(path: &Path) -> bool {
    let start = Instant::now();
    loop {
        if std::fs::remove_dir_all(path).is_ok() {
            return true;
        }
        if !path.exists() || start.elapsed() > FOLDER_REMOVAL_PATIENCE {
            return false;
        }
        std::thread::yield_now();
    }
}

/// Whether `name` follows our temporaries' naming pattern.
pub fn is_temporary_name(name: &str) -> bool {
    (name.starts_with(TEMPORARY_FILE_PREFIX) || name.starts_with(TEMPORARY_FOLDER_PREFIX))
        && name.ends_with(TEMPORARY_SUFFIX)
}

/// Deletes the temporaries of our naming pattern in `folder` that were not modified for
/// [`STALE_AFTER`] (left by a process that was killed); each folder once per process. Errors
/// are ignored: sweeping is a courtesy, never a reason to fail a write.
pub fn sweep_stale_temporaries(folder: &Path) {
    {
        let mut swept = SWEPT.lock().unwrap_or_else(|e| e.into_inner());
        if !swept
            .get_or_insert_with(HashSet::new)
            .insert(folder.to_path_buf())
        {
            return;
        }
    }
    let Ok(entries) = std::fs::read_dir(folder) else {
        return;
    };
    let now = SystemTime::now();
    for entry in entries.flatten() {
        let name = entry.file_name();
        if !is_temporary_name(&name.to_string_lossy()) {
            continue;
        }
        let Ok(metadata) = entry.path().symlink_metadata() else {
            continue;
        };
        let age = metadata
            .modified()
            .ok()
            .and_then(|m| now.duration_since(m).ok());
        if age.is_some_and(|a| a >= STALE_AFTER) {
            let path = entry.path();
            let _ = if metadata.is_dir() {
                std::fs::remove_dir_all(&path)
            } else {
                std::fs::remove_file(&path)
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn our_names_are_recognised_and_others_not() {
        assert!(is_temporary_name(".tvf-write-abc123.tmp"));
        assert!(is_temporary_name(".tvf-folder-abc123.tmp"));
        for other in ["tvf-write-a.tmp", ".tvf-write-a.npy", "x.tmp", ".tvf-cache"] {
            assert!(!is_temporary_name(other), "{other}");
        }
    }

    #[test]
    fn registered_temporaries_are_removed_and_stale_ones_swept() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join(".tvf-write-live.tmp");
        let folder = dir.path().join(".tvf-folder-live.tmp");
        let ((), file_guard) =
            create_registered(|| std::fs::write(&file, b"x"), |_| file.clone()).unwrap();
        let ((), folder_guard) =
            create_registered(|| std::fs::create_dir(&folder), |_| folder.clone()).unwrap();
        std::fs::write(folder.join("a.npy"), b"x").unwrap();
        let guards = [file_guard, folder_guard];
        // Only this test's temporaries: tests running at the same time register their own.
        assert_eq!(remove_registered(|p| p.starts_with(dir.path())), 2);
        assert!(!file.exists() && !folder.exists());
        drop(guards);

        // A fresh temporary (maybe another process's) stays; an old one of ours goes; other
        // files stay whatever their age.
        let fresh = dir.path().join(".tvf-write-fresh.tmp");
        let stale = dir.path().join(".tvf-write-stale.tmp");
        let mine = dir.path().join("keep.tmp");
        for p in [&fresh, &stale, &mine] {
            std::fs::write(p, b"x").unwrap();
        }
        let old = SystemTime::now() - 2 * STALE_AFTER;
        for p in [&stale, &mine] {
            std::fs::File::options()
                .write(true)
                .open(p)
                .unwrap()
                .set_modified(old)
                .unwrap();
        }
        sweep_stale_temporaries(dir.path());
        assert!(fresh.exists() && mine.exists() && !stale.exists());
    }

    /// A commit waits for no other of its own thread (nested commits run inside the outer
    /// one), and the removal of temporaries waits for a commit of another thread to end.
    #[test]
    fn removal_waits_for_a_commit_and_commits_nest() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join(".tvf-write-committing.tmp");
        let ((), guard) =
            create_registered(|| std::fs::write(&file, b"x"), |_| file.clone()).unwrap();
        let (entered, inside) = std::sync::mpsc::channel();
        let (release, released) = std::sync::mpsc::channel::<()>();
        let committer = std::thread::spawn(move || {
            commit_uninterrupted(|| {
                commit_uninterrupted(|| entered.send(()).unwrap());
                released.recv().unwrap();
                std::fs::rename(&file, file.with_extension("done")).unwrap();
            });
            drop(guard);
        });
        inside.recv().unwrap();
        let mine = dir.path().to_path_buf();
        let remover = std::thread::spawn(move || remove_registered(|p| p.starts_with(&mine)));
        std::thread::sleep(Duration::from_millis(100));
        assert!(
            !remover.is_finished(),
            "the removal did not wait for the commit"
        );
        release.send(()).unwrap();
        committer.join().unwrap();
        remover.join().unwrap();
        assert!(dir.path().join(".tvf-write-committing.done").exists());
    }

    /// A temporary being created when the removal begins is removed with the others: the
    /// removal waits for its creation and registration, which no interruption splits.
    #[test]
    fn removal_waits_for_a_temporary_being_created() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join(".tvf-folder-being-created.tmp");
        let (entered, creating) = std::sync::mpsc::channel();
        let creator = {
            let folder = folder.clone();
            std::thread::spawn(move || {
                create_registered(
                    || {
                        entered.send(()).unwrap();
                        std::thread::sleep(Duration::from_millis(100));
                        std::fs::create_dir(&folder)
                    },
                    |_| folder.clone(),
                )
                .map(|((), guard)| guard)
            })
        };
        creating.recv().unwrap();
        let mine = dir.path().to_path_buf();
        assert_eq!(remove_registered(|p| p.starts_with(&mine)), 1);
        assert!(!folder.exists());
        drop(creator.join().unwrap().unwrap());
    }

    /// A folder another thread goes on writing into while it is removed (files created after
    /// the removal listed the folder) is removed all the same.
    #[test]
    fn a_folder_written_into_while_it_is_removed_goes() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join(".tvf-folder-written.tmp");
        let ((), guard) =
            create_registered(|| std::fs::create_dir(&folder), |_| folder.clone()).unwrap();
        let (started, writing) = std::sync::mpsc::channel();
        let writer = {
            let folder = folder.clone();
            std::thread::spawn(move || {
                let mut written = 0;
                // Until the folder is gone, or a bounded number of files (so the removal ends
                // even on a slow machine): the writing of a process about to exit.
                while written < 1_000
                    && std::fs::write(folder.join(format!("{written}.npy")), b"x").is_ok()
                {
                    written += 1;
                    if written == 100 {
                        started.send(()).unwrap();
                    }
                }
                written
            })
        };
        writing.recv().unwrap();
        let mine = dir.path().to_path_buf();
        assert_eq!(remove_registered(|p| p.starts_with(&mine)), 1);
        let written = writer.join().unwrap();
        assert!(
            !folder.exists(),
            "the folder stayed ({written} files written)"
        );
        drop(guard);
    }

    /// Set in the child process of [`no_temporary_is_created_once_the_removal_began`]: the
    /// folder it works in.
    const CHILD_VARIABLE: &str = "TVF_TEMPORARIES_TEST_CHILD";

    /// Once [`remove_temporaries`] has run (the process is interrupted and about to exit), a
    /// new temporary is refused and not created. In a child process of this test binary: the
    /// registry stays closed for the rest of the process.
    #[test]
    fn no_temporary_is_created_once_the_removal_began() {
        if let Some(folder) = std::env::var_os(CHILD_VARIABLE) {
            let folder = PathBuf::from(folder);
            let before = folder.join(".tvf-write-before.tmp");
            let ((), _guard) =
                create_registered(|| std::fs::write(&before, b"x"), |_| before.clone()).unwrap();
            assert_eq!(remove_temporaries(), 1);
            let after = folder.join(".tvf-write-after.tmp");
            let refused = create_registered(|| std::fs::write(&after, b"x"), |_| after.clone());
            assert_eq!(
                refused.map(drop).unwrap_err().kind(),
                std::io::ErrorKind::Interrupted
            );
            std::fs::write(folder.join("checked"), b"").unwrap();
            return;
        }
        let dir = tempfile::tempdir().unwrap();
        let status = std::process::Command::new(std::env::current_exe().unwrap())
            .args([
                "io::temporaries::tests::no_temporary_is_created_once_the_removal_began",
                "--exact",
            ])
            .env(CHILD_VARIABLE, dir.path())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .status()
            .unwrap();
        assert!(status.success(), "the child's checks failed");
        let left: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(
            left,
            ["checked"],
            "the child did not run its checks to the end"
        );
    }
}
