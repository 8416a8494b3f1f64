//! Wavefront OBJ: `v x y z [w | r g b]` and `f i j k ...` lines (1-based or negative indices,
//! `i/t/n` forms, polygons fan-triangulated), `#` comments; everything else is ignored.
//!
//! Positions are parsed here (with line numbers), faces by `tobj`. `tobj` renumbers vertices in
//! order of first use per object and drops unused ones, so it is handed a copy of the file in
//! which vertex `k` is written as `v k 0 0`: the coordinates it returns are the file's vertex
//! numbers, and the correspondence positions ↔ indices survives exactly. Before that, a light
//! scan of every `f` line gives the errors `tobj` would report without a line number.

use super::error::LoadErrorKind;
use super::raw_mesh::{at, parse_error, Located, RawMesh};
use super::text::{check_finite, parse_coordinate, parse_integer, push_fan, strip_comment};
use std::fmt::Write as _;

/// Parses OBJ text into positions and fan-triangulated faces.
pub(crate) fn read_obj(text: &str) -> Result<RawMesh, Located> {
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut vertex_lines = Vec::new();
    // Corners of every face line (0-based, resolved) and the line number.
    let mut face_corners: Vec<(usize, Vec<i64>)> = Vec::new();
    // The copy of the file handed to tobj.
    let mut for_tobj = String::with_capacity(text.len() / 2);
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
                let _ = writeln!(for_tobj, "v {} 0 0", positions.len());
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
                for_tobj.push_str(content);
                for_tobj.push('\n');
            }
            "o" | "g" => {
                for_tobj.push_str(content);
                for_tobj.push('\n');
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
    let mut expected_faces = Vec::new();
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
        push_fan(&resolved, *line, &mut expected_faces, &mut face_lines);
    }

    let faces = faces_through_tobj(&for_tobj)?;
    // tobj keeps the file's face order; if it ever did not, line numbers would be wrong, so
    // they are only kept when its triangles are exactly those of the scan.
    let face_lines = if faces == expected_faces {
        face_lines
    } else {
        Vec::new()
    };
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

/// Runs tobj on the rewritten file and maps its vertices back to file vertex numbers.
fn faces_through_tobj(for_tobj: &str) -> Result<Vec<[usize; 3]>, Located> {
    // `..Default::default()` keeps this compiling (and those options off) if another crate
    // turns on tobj's `merging` or `reordering` features, which add fields.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let tobj_error = |e: tobj::LoadError| {
        (
            None,
            LoadErrorKind::Parse {
                message: format!("OBJ face data: {e}"),
            },
        )
    };
    let (models, _) = tobj::load_obj_buf(
        &mut std::io::Cursor::new(for_tobj.as_bytes()),
        &options,
        |_| Err(tobj::LoadError::OpenFileFailed),
    )
    .map_err(tobj_error)?;
    let mut faces = Vec::new();
    for model in &models {
        let mesh = &model.mesh;
        let original = |i: u32| -> Option<usize> {
            let x = *mesh.positions.get(3 * i as usize)?;
            (x >= 0.0 && x.fract() == 0.0).then_some(x as usize)
        };
        for triangle in mesh.indices.chunks_exact(3) {
            match [0, 1, 2].map(|c| original(triangle[c])) {
                [Some(a), Some(b), Some(c)] => faces.push([a, b, c]),
                _ => return Err(tobj_error(tobj::LoadError::GenericFailure)),
            }
        }
    }
    Ok(faces)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_negative_indices_and_comments() {
        let text = "# a square\nv 0 0 0\nv 1 0 0 # trailing comment\nv 1 1 0\nv 0 1 0\n\
                    f -4 -3 -2 -1\n";
        let raw = read_obj(text).unwrap();
        assert_eq!(raw.faces, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(raw.face_lines, vec![6, 6]);
        assert_eq!(raw.vertex_lines, vec![2, 3, 4, 5]);
    }

    #[test]
    fn duplicate_positions_keep_their_own_indices() {
        // tobj alone would merge nothing but renumber by first use; vertex 1 is used first.
        let text = "v 0 0 0\nv 1 0 0\nv 1 0 0\nv 0 1 0\nf 2/1 4 1\nf 3 4 1\n";
        let raw = read_obj(text).unwrap();
        assert_eq!(raw.faces, vec![[1, 3, 0], [2, 3, 0]]);
        assert_eq!(raw.positions.len(), 4);
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
