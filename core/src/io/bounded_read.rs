//! [`read_at_most`]: reading a whole input file with a cap on its size, so that an input that
//! never ends (a FIFO fed from `/dev/zero`) or is absurdly large is refused with a message
//! instead of being read until memory runs out.

use std::io::Read;
use std::path::Path;

/// Reads the file at `path` if it holds at most `limit` bytes; a longer one (or a stream that
/// goes on) is an [`std::io::ErrorKind::InvalidData`] error saying so. At most `limit + 1` bytes
/// are read.
pub fn read_at_most(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("larger than {limit} bytes, more than this kind of file can need"),
        ));
    }
    Ok(bytes)
}

/// Appends to `bytes` exactly `count` more bytes from `reader`, reading no more than that
/// (fewer if it ends first).
pub fn read_exactly_at_most(
    reader: &mut impl Read,
    count: u64,
    bytes: &mut Vec<u8>,
) -> std::io::Result<()> {
    reader.take(count).read_to_end(bytes).map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_up_to_the_limit_are_read_and_longer_ones_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f");
        std::fs::write(&path, b"12345").unwrap();
        assert_eq!(read_at_most(&path, 5).unwrap(), b"12345");
        let error = read_at_most(&path, 4).unwrap_err();
        assert!(error.to_string().contains("larger than 4 bytes"), "{error}");
        // An endless stream stops at the limit.
        let error = read_at_most(Path::new("/dev/zero"), 1000).unwrap_err();
        assert_eq!(error.kind(), std::io::ErrorKind::InvalidData);
        let mut bytes = Vec::new();
        read_exactly_at_most(&mut std::io::repeat(7).take(100), 10, &mut bytes).unwrap();
        assert_eq!(bytes, [7; 10]);
    }
}
