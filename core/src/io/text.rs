//! Helpers shared by the text readers: UTF-8 check, comment stripping, number parsing.

use super::error::LoadErrorKind;
use super::raw_mesh::{at, parse_error, Located};

/// The bytes as text; binary data is [`LoadErrorKind::NotText`] at the line where it starts.
pub(crate) fn as_text(bytes: &[u8]) -> Result<&str, Located> {
    std::str::from_utf8(bytes).map_err(|e| {
        let valid = &bytes[..e.valid_up_to()];
        let line = 1 + valid.iter().filter(|&&b| b == b'\n').count();
        at(line, LoadErrorKind::NotText)
    })
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

/// Appends the fan triangulation `(c0, c_{k}, c_{k+1})` of a polygon, recording its line.
pub(crate) fn push_fan(
    corners: &[usize],
    line: usize,
    faces: &mut Vec<[usize; 3]>,
    face_lines: &mut Vec<usize>,
) {
    for k in 1..corners.len().saturating_sub(1) {
        faces.push([corners[0], corners[k], corners[k + 1]]);
        face_lines.push(line);
    }
}
