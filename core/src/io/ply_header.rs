//! The header of a PLY file: format, elements and their properties.

use super::error::LoadErrorKind;
use super::raw_mesh::{at, parse_error, Located};

/// The scalar types of PLY, with their sizes in bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ScalarType {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl ScalarType {
    fn parse(name: &str, line: usize) -> Result<Self, Located> {
        Ok(match name {
            "char" | "int8" => Self::I8,
            "uchar" | "uint8" => Self::U8,
            "short" | "int16" => Self::I16,
            "ushort" | "uint16" => Self::U16,
            "int" | "int32" => Self::I32,
            "uint" | "uint32" => Self::U32,
            "float" | "float32" => Self::F32,
            "double" | "float64" => Self::F64,
            _ => return Err(parse_error(line, format!("unknown PLY type '{name}'"))),
        })
    }

    /// Size in bytes in a binary file.
    pub(crate) fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::F64 => 8,
        }
    }

    /// Whether the type is an integer type.
    pub(crate) fn is_integer(self) -> bool {
        !matches!(self, Self::F32 | Self::F64)
    }
}

/// One property of an element: a scalar, or a list with a count type and an item type.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Property {
    Scalar {
        name: String,
        ty: ScalarType,
    },
    List {
        name: String,
        count: ScalarType,
        item: ScalarType,
    },
}

impl Property {
    pub(crate) fn name(&self) -> &str {
        match self {
            Self::Scalar { name, .. } | Self::List { name, .. } => name,
        }
    }
}

/// An element declaration: `element NAME COUNT` followed by its properties.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Element {
    pub name: String,
    pub count: usize,
    pub properties: Vec<Property>,
}

/// How the body is encoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Encoding {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

/// A parsed header and where the body starts.
#[derive(Debug, Clone)]
pub(crate) struct Header {
    pub encoding: Encoding,
    pub elements: Vec<Element>,
    /// Byte offset of the first body byte.
    pub body_start: usize,
    /// Number of header lines (the body's first line is `header_lines + 1`).
    pub header_lines: usize,
}

/// Parses the header at the start of `bytes`.
pub(crate) fn read_header(bytes: &[u8]) -> Result<Header, Located> {
    if bytes.is_empty() {
        return Err((None, LoadErrorKind::Empty));
    }
    if !bytes.starts_with(b"ply") {
        return Err(parse_error(1, "a PLY file must start with 'ply'"));
    }
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut offset = 0;
    let mut line = 0;
    loop {
        let Some(length) = bytes[offset..].iter().position(|&b| b == b'\n') else {
            return Err(at(
                line + 1,
                LoadErrorKind::Truncated {
                    message: "the header has no 'end_header' line".into(),
                },
            ));
        };
        line += 1;
        let raw = &bytes[offset..offset + length];
        offset += length + 1;
        let text = std::str::from_utf8(raw).map_err(|_| at(line, LoadErrorKind::NotText))?;
        let tokens: Vec<&str> = text.split_whitespace().collect();
        match tokens.as_slice() {
            ["ply"] if line == 1 => {}
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", _, version] if *version != "1.0" => {
                return Err(parse_error(
                    line,
                    format!("PLY version '{version}' is not supported (only 1.0)"),
                ))
            }
            ["format", format, _version] => {
                encoding = Some(match *format {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::BinaryLittleEndian,
                    "binary_big_endian" => Encoding::BinaryBigEndian,
                    other => {
                        return Err(parse_error(line, format!("unknown PLY format '{other}'")))
                    }
                })
            }
            ["element", name, count] => {
                let count = count
                    .parse::<usize>()
                    .map_err(|_| parse_error(line, format!("bad element count '{count}'")))?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    properties: Vec::new(),
                });
            }
            ["property", rest @ ..] => {
                let Some(element) = elements.last_mut() else {
                    return Err(parse_error(line, "a property before any element"));
                };
                let property = match rest {
                    ["list", count, item, name] => Property::List {
                        name: name.to_string(),
                        count: ScalarType::parse(count, line)?,
                        item: ScalarType::parse(item, line)?,
                    },
                    [ty, name] => Property::Scalar {
                        name: name.to_string(),
                        ty: ScalarType::parse(ty, line)?,
                    },
                    _ => return Err(parse_error(line, format!("malformed property '{text}'"))),
                };
                if let Property::List { count, .. } = &property {
                    if !count.is_integer() {
                        return Err(parse_error(line, "a list count must have an integer type"));
                    }
                }
                element.properties.push(property);
            }
            ["end_header"] => break,
            _ => {
                return Err(parse_error(
                    line,
                    format!("unexpected PLY header line '{text}'"),
                ))
            }
        }
    }
    let Some(encoding) = encoding else {
        return Err(parse_error(line, "the header has no 'format' line"));
    };
    Ok(Header {
        encoding,
        elements,
        body_start: offset,
        header_lines: line,
    })
}
