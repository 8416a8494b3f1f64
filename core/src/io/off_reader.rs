//! Object File Format: an `OFF` header (also `COFF`, `NOFF`, `CNOFF`, `STOFF`...; extra
//! per-vertex values are ignored), the counts `V F [E]`, `V` vertex lines `x y z ...`, then `F`
//! face lines `n i_0 ... i_{n−1} [colour]` with 0-based indices; `#` comments.

use super::error::LoadErrorKind;
use super::raw_mesh::{at, parse_error, Located, RawMesh};
use super::text::{
    check_finite, parse_coordinate, parse_integer, push_face, strip_comment, vertex_index,
};

/// Parses OFF text into positions and faces (polygons kept).
pub(crate) fn read_off(text: &str) -> Result<RawMesh, Located> {
    // Non-empty lines after comment removal, with their 1-based numbers.
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, strip_comment(l).trim()))
        .filter(|(_, l)| !l.is_empty());
    let Some((header_line, header)) = lines.next() else {
        return Err((None, LoadErrorKind::Empty));
    };
    let mut header_tokens = header.split_whitespace();
    let keyword = header_tokens.next().unwrap_or("");
    if !keyword.ends_with("OFF") {
        return Err(parse_error(
            header_line,
            format!("expected an OFF header, found '{keyword}'"),
        ));
    }
    if keyword.contains('n') || keyword.starts_with('4') {
        return Err(at(
            header_line,
            LoadErrorKind::Unsupported {
                feature: format!("OFF variant '{keyword}' (only 3D OFF is read)"),
            },
        ));
    }
    // The counts may follow the keyword on the same line.
    let mut counts: Vec<&str> = header_tokens.collect();
    let mut counts_line = header_line;
    if counts.is_empty() {
        let Some((line, text)) = lines.next() else {
            return Err(at(
                header_line,
                LoadErrorKind::Truncated {
                    message: "no vertex and face counts after the header".into(),
                },
            ));
        };
        counts = text.split_whitespace().collect();
        counts_line = line;
    }
    if counts.len() < 2 || counts.len() > 3 {
        return Err(parse_error(
            counts_line,
            format!("expected 'V F [E]' counts, found {} values", counts.len()),
        ));
    }
    let count = |token: &str| -> Result<usize, Located> {
        let value = parse_integer(token, counts_line)?;
        usize::try_from(value)
            .map_err(|_| parse_error(counts_line, format!("negative count {value}")))
    };
    let (vertex_count, face_count) = (count(counts[0])?, count(counts[1])?);

    let mut raw = RawMesh::default();
    let mut last_line = counts_line;
    for v in 0..vertex_count {
        let Some((line, text)) = lines.next() else {
            return Err(at(
                last_line,
                LoadErrorKind::Truncated {
                    message: format!("the header declares {vertex_count} vertices, found {v}"),
                },
            ));
        };
        last_line = line;
        let values = text
            .split_whitespace()
            .take(3)
            .map(|t| parse_coordinate(t, line))
            .collect::<Result<Vec<_>, _>>()?;
        let [x, y, z] = values[..] else {
            return Err(parse_error(
                line,
                format!("a vertex needs 3 coordinates, found {}", values.len()),
            ));
        };
        check_finite([x, y, z], v, line)?;
        raw.positions.push([x, y, z]);
        raw.vertex_lines.push(line);
    }
    for f in 0..face_count {
        let Some((line, text)) = lines.next() else {
            return Err(at(
                last_line,
                LoadErrorKind::Truncated {
                    message: format!("the header declares {face_count} faces, found {f}"),
                },
            ));
        };
        last_line = line;
        let mut tokens = text.split_whitespace();
        let n = parse_integer(tokens.next().unwrap_or(""), line)?;
        let n = usize::try_from(n).unwrap_or(0);
        let corners = tokens
            .take(n)
            .map(|t| vertex_index(parse_integer(t, line)?, vertex_count, line))
            .collect::<Result<Vec<_>, _>>()?;
        if corners.len() < n {
            return Err(parse_error(
                line,
                format!("the face declares {n} corners, found {}", corners.len()),
            ));
        }
        if n < 3 {
            return Err(at(line, LoadErrorKind::FaceTooSmall { corners: n }));
        }
        push_face(&corners, line, &mut raw.faces, &mut raw.face_lines);
    }
    if let Some((line, text)) = lines.next() {
        return Err(at(
            line,
            LoadErrorKind::TrailingData {
                message: format!("'{text}' after {vertex_count} vertices and {face_count} faces"),
            },
        ));
    }
    Ok(raw)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_with_counts_on_header_line() {
        let raw = read_off("OFF 4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n").unwrap();
        assert_eq!(raw.faces, crate::FaceList::from_polygons(&[[0, 1, 2, 3]]));
        assert_eq!(raw.face_lines, vec![6]);
    }

    #[test]
    fn missing_faces_are_truncation() {
        let err = read_off("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap_err();
        assert!(matches!(err, (Some(6), LoadErrorKind::Truncated { .. })));
    }
}
