//! Helpers shared by the text readers: UTF-8 check, comment stripping, number parsing.

use super::error::LoadErrorKind;
use super::raw_mesh::{at, parse_error, Located};
use crate::mesh::FaceList;
use std::borrow::Cow;

/// The bytes as text. Comments (`#` to the end of the line) may hold any bytes (old tools write
/// them in Latin-1); elsewhere bytes that are not UTF-8 are [`LoadErrorKind::NotText`] at their
/// line, and a UTF-16 file is [`LoadErrorKind::Utf16`]. Lines that end in a carriage return
/// only (old Mac files) are read as lines.
pub(crate) fn as_text(bytes: &[u8]) -> Result<Cow<'_, str>, Located> {
    if is_utf16_text(bytes) {
        return Err(at(1, LoadErrorKind::Utf16));
    }
    let text = match std::str::from_utf8(bytes) {
        Ok(text) => Cow::Borrowed(text),
        Err(_) => Cow::Owned(without_comments(bytes)?),
    };
    if !text.contains('\n') && text.contains('\r') {
        return Ok(Cow::Owned(text.replace('\r', "\n")));
    }
    Ok(text)
}

/// Whether `bytes` are UTF-16 text: a byte-order mark, then code units that decode without
/// error into characters that are not control characters other than line ends and tabs.
fn is_utf16_text(bytes: &[u8]) -> bool {
    let little_endian = match bytes {
        [0xFF, 0xFE, ..] => true,
        [0xFE, 0xFF, ..] => false,
        _ => return false,
    };
    let units = bytes[2..].chunks_exact(2).map(|pair| {
        let pair = [pair[0], pair[1]];
        if little_endian {
            u16::from_le_bytes(pair)
        } else {
            u16::from_be_bytes(pair)
        }
    });
    bytes.len().is_multiple_of(2)
        && char::decode_utf16(units)
            .all(|c| c.is_ok_and(|c| !c.is_control() || matches!(c, '\n' | '\r' | '\t')))
}

/// The lines of `bytes` with their comments cut off (line numbers kept), which must be UTF-8.
fn without_comments(bytes: &[u8]) -> Result<String, Located> {
    let mut text = String::with_capacity(bytes.len());
    for (number, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let content = match line.iter().position(|&b| b == b'#') {
            Some(k) => &line[..k],
            None => line,
        };
        let content =
            std::str::from_utf8(content).map_err(|_| at(number + 1, LoadErrorKind::NotText))?;
        if number > 0 {
            text.push('\n');
        }
        text.push_str(content);
    }
    Ok(text)
}

/// The part of `line` before a `#` comment.
pub(crate) fn strip_comment(line: &str) -> &str {
    match line.find('#') {
        Some(i) => &line[..i],
        None => line,
    }
}

/// Parses a coordinate; `nan`/`inf` parse (and are rejected later as non-finite).
pub(crate) fn parse_coordinate(token: &str, line: usize) -> Result<f64, Located> {
    token
        .parse::<f64>()
        .map_err(|_| parse_error(line, format!("'{token}' is not a number")))
}

/// Parses an integer (an index or a count).
pub(crate) fn parse_integer(token: &str, line: usize) -> Result<i64, Located> {
    token
        .parse::<i64>()
        .map_err(|_| parse_error(line, format!("'{token}' is not an integer")))
}

/// Fails with [`LoadErrorKind::NonFiniteCoordinate`] if `p` has a NaN or infinite entry.
pub(crate) fn check_finite(p: [f64; 3], vertex: usize, line: usize) -> Result<(), Located> {
    if p.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(at(line, LoadErrorKind::NonFiniteCoordinate { vertex }))
    }
}

/// Converts a 0-based index read from the file into a vertex number, or fails.
pub(crate) fn vertex_index(index: i64, vertex_count: usize, line: usize) -> Result<usize, Located> {
    match usize::try_from(index) {
        Ok(v) if v < vertex_count => Ok(v),
        _ => Err(at(
            line,
            LoadErrorKind::IndexOutOfRange {
                index,
                vertex_count,
            },
        )),
    }
}

/// Appends a face with `corners` (already resolved to 0-based indices) read at `line` to
/// `faces`, and its line to `face_lines`.
pub(crate) fn push_face(
    corners: &[usize],
    line: usize,
    faces: &mut FaceList,
    face_lines: &mut Vec<usize>,
) {
    faces.push(corners);
    face_lines.push(line);
}
