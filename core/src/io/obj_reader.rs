//! Wavefront OBJ: `v x y z [w | r g b]` and `f i j k ...` lines (1-based or negative indices,
//! `i/t/n` forms, polygons kept as polygons), `#` comments; everything else is ignored.
//!
//! A hand-written parser, not `tobj`: tvf reads only `v` and `f` lines, and needs what `tobj`
//! does not give: every error names its line (a malformed number, a zero or out-of-range
//! index, a face with fewer than three corners), vertices keep the file's numbering (`tobj`
//! renumbers them by first use per object and drops unused ones), and each triangle knows the
//! line of its face. Positive indices may point forward in the file, so they are checked
//! against the final vertex count after the whole file is read.

use super::error::LoadErrorKind;
use super::raw_mesh::{at, parse_error, Located, RawMesh};
use super::text::{check_finite, parse_coordinate, parse_integer, push_face, strip_comment};
use crate::mesh::FaceList;

/// Parses OBJ text into positions and faces (polygons kept).
pub(crate) fn read_obj(text: &str) -> Result<RawMesh, Located> {
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut vertex_lines = Vec::new();
    // Corners of every face line (0-based, resolved) and the line number.
    let mut face_corners: Vec<(usize, Vec<i64>)> = Vec::new();
    let mut any_content = false;

    for (number, raw_line) in text.lines().enumerate() {
        let line = number + 1;
        let content = strip_comment(raw_line);
        let mut tokens = content.split_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        any_content = true;
        match keyword {
            "v" => {
                let values = tokens
                    .map(|t| parse_coordinate(t, line))
                    .collect::<Result<Vec<_>, _>>()?;
                let p = match values.as_slice() {
                    [x, y, z] | [x, y, z, _, _, _] => [*x, *y, *z],
                    [x, y, z, w] if *w != 0.0 => [x / w, y / w, z / w],
                    [_, _, _, _] => return Err(parse_error(line, "vertex weight w is zero")),
                    _ => {
                        return Err(parse_error(
                            line,
                            format!("a vertex needs 3 coordinates, found {}", values.len()),
                        ))
                    }
                };
                check_finite(p, positions.len(), line)?;
                positions.push(p);
                vertex_lines.push(line);
            }
            "f" => {
                let mut corners = Vec::new();
                for token in tokens {
                    corners.push(face_corner(token, positions.len(), line)?);
                }
                if corners.len() < 3 {
                    return Err(at(
                        line,
                        LoadErrorKind::FaceTooSmall {
                            corners: corners.len(),
                        },
                    ));
                }
                face_corners.push((line, corners));
            }
            // Other keywords (vt, vn, usemtl, ...) are ignored; one that is not a plain word
            // (a stray byte-order mark or control character before a `v`) would hide its line.
            other if !other.bytes().all(|b| b.is_ascii_graphic()) => {
                return Err(parse_error(
                    line,
                    format!("'{other}' is not an OBJ keyword (unexpected characters)"),
                ))
            }
            _ => {}
        }
    }
    if !any_content {
        return Err((None, LoadErrorKind::Empty));
    }

    // Positive indices may point forward in the file; check them against the final count.
    let vertex_count = positions.len();
    let mut face_lines = Vec::new();
    let mut faces = FaceList::new();
    for (line, corners) in &face_corners {
        let mut resolved = Vec::with_capacity(corners.len());
        for &index in corners {
            let v = if index > 0 { index - 1 } else { index };
            match usize::try_from(v) {
                Ok(v) if v < vertex_count => resolved.push(v),
                _ => {
                    return Err(at(
                        *line,
                        LoadErrorKind::IndexOutOfRange {
                            index,
                            vertex_count,
                        },
                    ))
                }
            }
        }
        push_face(&resolved, *line, &mut faces, &mut face_lines);
    }
    Ok(RawMesh {
        positions,
        faces,
        vertex_lines,
        face_lines,
    })
}

/// Parses one `v`, `v/t`, `v//n` or `v/t/n` corner; negative indices are resolved against the
/// `seen` vertices so far and returned as 0-based values `< 0` only if out of range.
fn face_corner(token: &str, seen: usize, line: usize) -> Result<i64, Located> {
    let mut parts = token.split('/');
    let index = parse_integer(parts.next().unwrap_or(""), line)?;
    let mut extra = 0;
    for part in parts {
        extra += 1;
        if extra > 2 || (!part.is_empty() && part.parse::<i64>().is_err()) {
            return Err(parse_error(
                line,
                format!("malformed face corner '{token}'"),
            ));
        }
    }
    match index {
        0 => Err(at(
            line,
            LoadErrorKind::IndexOutOfRange {
                index: 0,
                vertex_count: seen,
            },
        )),
        i if i < 0 => {
            let resolved = seen as i64 + i;
            if resolved < 0 {
                Err(at(
                    line,
                    LoadErrorKind::IndexOutOfRange {
                        index: i,
                        vertex_count: seen,
                    },
                ))
            } else {
                // As a positive 1-based index from here on.
                Ok(resolved + 1)
            }
        }
        i => Ok(i),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_negative_indices_and_comments() {
        let text = "# a square\nv 0 0 0\nv 1 0 0 # trailing comment\nv 1 1 0\nv 0 1 0\n\
                    f -4 -3 -2 -1\n";
        let raw = read_obj(text).unwrap();
        assert_eq!(raw.faces, FaceList::from_polygons(&[[0, 1, 2, 3]]));
        assert_eq!(raw.face_lines, vec![6]);
        assert_eq!(raw.vertex_lines, vec![2, 3, 4, 5]);
    }

    #[test]
    fn duplicate_positions_keep_their_own_indices() {
        // Vertex 1 is used first, vertex 0 last: the file's numbering is kept all the same.
        let text = "v 0 0 0\nv 1 0 0\nv 1 0 0\nv 0 1 0\nf 2/1 4 1\nf 3 4 1\n";
        let raw = read_obj(text).unwrap();
        assert_eq!(
            raw.faces.to_triangles().unwrap(),
            vec![[1, 3, 0], [2, 3, 0]]
        );
        assert_eq!(raw.positions.len(), 4);
    }

    #[test]
    fn objects_and_groups_keep_the_file_numbering_and_forward_indices_resolve() {
        // Each `o`/`g` starts an object for tobj (renumbered from 0 there); here the indices
        // stay the file's, a face may name a vertex defined after it, and `vt`/`vn` are skipped.
        let text = "o first\nv 0 0 0\nv 1 0 0\nf 1 2 3\ng second\nvt 0 0\nv 0 1 0\n\
                    vn 0 0 1\nv 1 1 0\nf 4/1/1 3//1 2\n";
        let raw = read_obj(text).unwrap();
        assert_eq!(
            raw.faces.to_triangles().unwrap(),
            vec![[0, 1, 2], [3, 2, 1]]
        );
        assert_eq!(raw.face_lines, vec![4, 10]);
        assert_eq!(raw.vertex_lines, vec![2, 3, 7, 9]);
    }

    #[test]
    fn forward_index_past_the_end_names_its_line() {
        let err = read_obj("v 0 0 0\nf 1 2 4\nv 1 0 0\nv 0 1 0\n").unwrap_err();
        assert_eq!(
            err,
            at(
                2,
                LoadErrorKind::IndexOutOfRange {
                    index: 4,
                    vertex_count: 3
                }
            )
        );
    }

    #[test]
    fn zero_index_is_out_of_range_with_line() {
        let err = read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").unwrap_err();
        assert_eq!(
            err,
            at(
                4,
                LoadErrorKind::IndexOutOfRange {
                    index: 0,
                    vertex_count: 3
                }
            )
        );
    }
}
