//! PLY, ASCII or binary (little- or big-endian): the `vertex` element's `x y z` (any scalar type) and the
//! `face` element's `vertex_indices` (or `vertex_index`) list (any integer types); every other
//! property and element is read past and ignored.

use super::error::LoadErrorKind;
use super::ply_header::{read_header, Element, Encoding, Property, ScalarType};
use super::raw_mesh::{at, parse_error, Located, RawMesh};
use super::text::{check_finite, push_face, vertex_index};
use std::str::SplitWhitespace;

/// Parses a PLY file into positions and faces (polygons kept).
pub(crate) fn read_ply(bytes: &[u8]) -> Result<RawMesh, Located> {
    let header = read_header(bytes)?;
    let body = &bytes[header.body_start..];
    let mut source = match header.encoding {
        Encoding::Ascii => {
            let text = std::str::from_utf8(body).map_err(|e| {
                let valid = &body[..e.valid_up_to()];
                let line = header.header_lines + 1 + valid.iter().filter(|&&b| b == b'\n').count();
                at(line, LoadErrorKind::NotText)
            })?;
            Source::Ascii(AsciiBody::new(text, header.header_lines))
        }
        Encoding::BinaryLittleEndian => Source::Binary {
            body,
            offset: 0,
            big_endian: false,
        },
        Encoding::BinaryBigEndian => Source::Binary {
            body,
            offset: 0,
            big_endian: true,
        },
    };
    let vertex_count = header
        .elements
        .iter()
        .find(|e| e.name == "vertex")
        .map(|e| e.count)
        .ok_or_else(|| parse_error(header.header_lines, "the PLY header has no vertex element"))?;

    let mut raw = RawMesh::default();
    for element in &header.elements {
        let role = Role::of(element, header.header_lines)?;
        if element.properties.is_empty() {
            // Nothing is stored per instance: no data to read, however large the count
            // (iterating a count of 10^18 would hang).
            continue;
        }
        for instance in 0..element.count {
            let line = source.line();
            let fail = |error: Option<Located>| {
                error.unwrap_or_else(|| {
                    let message = format!(
                        "the data ends in element '{}' {instance} of {}",
                        element.name, element.count
                    );
                    (line, LoadErrorKind::Truncated { message })
                })
            };
            let mut xyz = [0.0; 3];
            let mut corners = Vec::new();
            for (p, property) in element.properties.iter().enumerate() {
                match property {
                    Property::Scalar { ty, .. } => {
                        let value = source.number(*ty).map_err(fail)?;
                        if let Role::Vertex(axes) = &role {
                            if let Some(axis) = axes.iter().position(|&a| a == p) {
                                xyz[axis] = value;
                            }
                        }
                    }
                    Property::List { count, item, .. } => {
                        let n = source.number(*count).map_err(fail)?;
                        let n = if n >= 0.0 { n as usize } else { 0 };
                        let wanted = matches!(role, Role::Face(q) if q == p);
                        if !wanted {
                            source.skip(*item, n).map_err(fail)?;
                            continue;
                        }
                        for _ in 0..n {
                            let index = source.number(*item).map_err(fail)?;
                            let line_or_0 = line.unwrap_or(0);
                            let v = vertex_index(index as i64, vertex_count, line_or_0)
                                .map_err(|(_, kind)| (line, kind))?;
                            corners.push(v);
                        }
                    }
                }
            }
            match role {
                Role::Vertex(_) => {
                    let vertex = raw.positions.len();
                    check_finite(xyz, vertex, line.unwrap_or(0)).map_err(|(_, k)| (line, k))?;
                    raw.positions.push(xyz);
                    raw.vertex_lines.extend(line);
                }
                Role::Face(_) => {
                    if corners.len() < 3 {
                        let corners = corners.len();
                        return Err((line, LoadErrorKind::FaceTooSmall { corners }));
                    }
                    let before = raw.face_lines.len();
                    push_face(
                        &corners,
                        line.unwrap_or(0),
                        &mut raw.faces,
                        &mut raw.face_lines,
                    );
                    if line.is_none() {
                        raw.face_lines.truncate(before);
                    }
                }
                Role::Other => {}
            }
        }
    }
    source.finish()?;
    Ok(raw)
}

/// What an element contributes.
enum Role {
    /// The vertex element, with the property positions of x, y, z.
    Vertex([usize; 3]),
    /// The face element, with the property position of the index list.
    Face(usize),
    /// Anything else (read past).
    Other,
}

impl Role {
    fn of(element: &Element, header_line: usize) -> Result<Self, Located> {
        let find = |name: &str| element.properties.iter().position(|p| p.name() == name);
        match element.name.as_str() {
            "vertex" => match [find("x"), find("y"), find("z")] {
                [Some(x), Some(y), Some(z)]
                    if [x, y, z]
                        .iter()
                        .all(|&p| matches!(element.properties[p], Property::Scalar { .. })) =>
                {
                    Ok(Role::Vertex([x, y, z]))
                }
                _ => Err(parse_error(
                    header_line,
                    "the PLY vertex element needs scalar x, y and z properties",
                )),
            },
            "face" => match find("vertex_indices").or_else(|| find("vertex_index")) {
                Some(p) => match element.properties[p] {
                    Property::List { item, .. } if item.is_integer() => Ok(Role::Face(p)),
                    _ => Err(parse_error(
                        header_line,
                        "the PLY face element's vertex_indices must be a list of integers",
                    )),
                },
                None => Err(parse_error(
                    header_line,
                    "the PLY face element has no vertex_indices list",
                )),
            },
            _ => Ok(Role::Other),
        }
    }
}

/// Where the body's numbers come from. Errors are `Some(error)`, or `None` for "ran out"
/// (the caller turns that into a truncation message naming the element).
enum Source<'a> {
    Ascii(AsciiBody<'a>),
    /// Binary values; `big_endian` says their byte order.
    Binary {
        body: &'a [u8],
        offset: usize,
        big_endian: bool,
    },
}

/// Result of reading one value: `Err(None)` means the data ended.
type Read<T> = Result<T, Option<Located>>;

impl Source<'_> {
    /// 1-based line of the next value (ASCII only).
    fn line(&mut self) -> Option<usize> {
        match self {
            Source::Ascii(body) => Some(body.next_line()),
            Source::Binary { .. } => None,
        }
    }

    /// Reads one value of type `ty` as `f64` (exact for every integer type of PLY).
    fn number(&mut self, ty: ScalarType) -> Read<f64> {
        match self {
            Source::Ascii(body) => {
                let (token, line) = body.next_token().ok_or(None)?;
                let value = if ty.is_integer() {
                    token.parse::<i64>().map(|v| v as f64).ok()
                } else {
                    token.parse::<f64>().ok()
                };
                value.ok_or_else(|| {
                    Some(parse_error(
                        line,
                        format!("'{token}' is not a valid {ty:?}"),
                    ))
                })
            }
            Source::Binary {
                body,
                offset,
                big_endian,
            } => {
                let size = ty.size();
                let bytes = body.get(*offset..*offset + size).ok_or(None)?;
                *offset += size;
                // Little-endian from here on: a big-endian value's bytes are reversed.
                let mut b = [0u8; 8];
                b[..size].copy_from_slice(bytes);
                if *big_endian {
                    b[..size].reverse();
                }
                Ok(match ty {
                    ScalarType::I8 => i8::from_le_bytes([b[0]]) as f64,
                    ScalarType::U8 => b[0] as f64,
                    ScalarType::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
                    ScalarType::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
                    ScalarType::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    ScalarType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    ScalarType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
                    ScalarType::F64 => f64::from_le_bytes(b),
                })
            }
        }
    }

    /// Skips `n` values of type `ty` without storing them.
    fn skip(&mut self, ty: ScalarType, n: usize) -> Read<()> {
        match self {
            Source::Ascii(_) => (0..n).try_for_each(|_| self.number(ty).map(|_| ())),
            Source::Binary { body, offset, .. } => {
                let end = n
                    .checked_mul(ty.size())
                    .and_then(|bytes| offset.checked_add(bytes))
                    .filter(|&end| end <= body.len())
                    .ok_or(None)?;
                *offset = end;
                Ok(())
            }
        }
    }

    /// Fails if anything but whitespace (ASCII) or anything at all (binary) is left.
    fn finish(mut self) -> Result<(), Located> {
        match &mut self {
            Source::Ascii(body) => match body.next_token() {
                Some((token, line)) => Err(at(
                    line,
                    LoadErrorKind::TrailingData {
                        message: format!("'{token}'"),
                    },
                )),
                None => Ok(()),
            },
            Source::Binary { body, offset, .. } if *offset < body.len() => Err((
                None,
                LoadErrorKind::TrailingData {
                    message: format!("{} bytes", body.len() - *offset),
                },
            )),
            Source::Binary { .. } => Ok(()),
        }
    }
}

/// Whitespace-separated tokens of an ASCII body, with line numbers.
struct AsciiBody<'a> {
    lines: std::str::Lines<'a>,
    tokens: SplitWhitespace<'a>,
    /// Line of the most recent token (or of the body start).
    line: usize,
}

impl<'a> AsciiBody<'a> {
    fn new(text: &'a str, header_lines: usize) -> Self {
        Self {
            lines: text.lines(),
            tokens: "".split_whitespace(),
            line: header_lines,
        }
    }

    /// Line of the next token (the last line if none is left).
    fn next_line(&mut self) -> usize {
        while self.tokens.clone().next().is_none() {
            match self.lines.next() {
                Some(text) => {
                    self.tokens = text.split_whitespace();
                    self.line += 1;
                }
                None => break,
            }
        }
        self.line
    }

    fn next_token(&mut self) -> Option<(&'a str, usize)> {
        loop {
            if let Some(token) = self.tokens.next() {
                return Some((token, self.line));
            }
            self.tokens = self.lines.next()?.split_whitespace();
            self.line += 1;
        }
    }
}
