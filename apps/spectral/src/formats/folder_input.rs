//! Opening the files of an input folder (a complex folder's matrices, `info.json`,
//! `vertex_map.npy`) so that no file can make a reader hang or read without end: only regular
//! files are read (a link to one is followed; a FIFO, a device such as `/dev/zero` or a socket is
//! refused, and opened without waiting for a writer first), never more bytes than the file held
//! when it was opened, and names that come from the folder's own files stay inside it.

use std::fs::File;
use std::io::Read;
use std::path::Path;

/// A regular file opened for reading, with its length when opened.
pub(crate) struct InputFile {
    /// The file.
    pub file: File,
    /// Its length in bytes.
    pub bytes: u64,
}

impl InputFile {
    /// The file, reading at most the bytes it held when opened (a file that grows while it is
    /// read, such as some of `/proc`, is read no further).
    pub fn bounded(self) -> std::io::Take<File> {
        let bytes = self.bytes;
        self.file.take(bytes)
    }
}

/// Opens `path` if it is a regular file (after following links). A FIFO is opened without
/// waiting for a writer (`O_NONBLOCK` on Unix) and refused like every other special file, with
/// a message saying what it is.
pub(crate) fn open_regular_file(path: &Path) -> Result<InputFile, String> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // Without it, opening a FIFO blocks until someone writes to it; on a regular file it
        // changes nothing.
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(|e| e.to_string())?;
    let metadata = file.metadata().map_err(|e| e.to_string())?;
    if !metadata.is_file() {
        return Err(format!(
            "not a regular file ({}): the files of a folder are read only if they are regular \
             files",
            special_kind(&metadata)
        ));
    }
    Ok(InputFile {
        file,
        bytes: metadata.len(),
    })
}

/// Reads the whole regular file `path` if it holds at most `limit` bytes.
pub(crate) fn read_small_file(path: &Path, limit: u64) -> Result<Vec<u8>, String> {
    let input = open_regular_file(path)?;
    if input.bytes > limit {
        return Err(format!(
            "{} bytes: larger than the {limit} bytes this kind of file can need",
            input.bytes
        ));
    }
    let mut bytes = Vec::with_capacity(input.bytes as usize);
    input
        .bounded()
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}

/// What kind of special file `metadata` describes ("a FIFO", "a character device" …).
fn special_kind(metadata: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let kind = metadata.file_type();
        if kind.is_fifo() {
            return "a FIFO";
        }
        if kind.is_char_device() {
            return "a character device";
        }
        if kind.is_block_device() {
            return "a block device";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    if metadata.is_dir() {
        "a folder"
    } else {
        "a special file"
    }
}

/// Whether `name`, read from a file of a folder, names a file of that folder itself: a plain
/// name, not absolute, without separators, and not `.` or `..`.
pub(crate) fn is_plain_file_name(name: &str) -> bool {
    let leaves = [
        name.is_empty(),
        name == "." || name == "..",
        name.contains(['/', '\\', '\0']),
        Path::new(name).is_absolute(),
        // A Windows drive (`C:x`).
        name.as_bytes().get(1) == Some(&b':'),
    ];
    !leaves.contains(&true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_files_are_refused_without_waiting() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("f");
        std::fs::write(&file, b"hello").unwrap();
        assert_eq!(read_small_file(&file, 5).unwrap(), b"hello");
        assert!(read_small_file(&file, 4)
            .unwrap_err()
            .contains("larger than"));
        let message = open_regular_file(dir.path()).err().unwrap();
        assert!(
            message.contains("folder") || message.contains("directory"),
            "{message}"
        );
        #[cfg(unix)]
        {
            let zero = dir.path().join("zero");
            std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
            let message = open_regular_file(&zero).err().unwrap();
            assert!(message.contains("character device"), "{message}");
            let fifo = dir.path().join("fifo");
            let made = std::process::Command::new("mkfifo").arg(&fifo).status();
            assert!(made.unwrap().success());
            // No writer: this would wait forever without O_NONBLOCK.
            let message = open_regular_file(&fifo).err().unwrap();
            assert!(message.contains("a FIFO"), "{message}");
        }
    }

    #[test]
    fn names_stay_inside_the_folder() {
        for good in ["M1", "M1_inverse", "my mass.v2"] {
            assert!(is_plain_file_name(good), "{good}");
        }
        for bad in ["", ".", "..", "../M1", "/etc/passwd", "a/b", "a\\b", "C:x"] {
            assert!(!is_plain_file_name(bad), "{bad}");
        }
    }
}
