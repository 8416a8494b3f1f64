//! NumPy `.npy` arrays of numbers (format versions 1.0, 2.0 and 3.0), read and written with the
//! `npyz` crate.
//!
//! Read: float (`f4`, `f8`) and integer (`i1`…`i8`, `u1`…`u8`) dtypes of either byte order, in
//! C or Fortran order, any number of dimensions; the values come back as `f64` in C order
//! (integers converted exactly: one beyond ±2⁵³ that `f64` cannot hold is refused). Everything
//! else (booleans, complex, strings, records, truncated or over-long data) is refused with a
//! [`NpyError`] saying why. The first bytes (magic, version, header length) are checked here
//! before `npyz` parses the header, so a bounded reader knows how much to read and an absurd
//! header length is refused before it is read ([`MAX_HEADER_BYTES`]).
//!
//! Written: little-endian `f4`/`f8` in C order ([`NpyArray::to_bytes`]), the header padded so
//! that the data start at a multiple of 64 bytes.

use npyz::{DType, Deserialize, NpyFile, NpyHeader, Order, TypeChar, TypeStr, WriterBuilder};
use thiserror::Error;

/// The magic string every `.npy` file starts with.
const MAGIC: &[u8; 6] = b"\x93NUMPY";

/// Element type of an `.npy` array tvf writes (and of a float array it read).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NpyDtype {
    /// Little-endian IEEE single precision (`<f4`).
    F32,
    /// Little-endian IEEE double precision (`<f8`).
    F64,
}

impl NpyDtype {
    /// The dtype string of the header (`<f4` or `<f8`).
    pub fn descr(self) -> &'static str {
        match self {
            NpyDtype::F32 => "<f4",
            NpyDtype::F64 => "<f8",
        }
    }

    /// Bytes per element.
    pub fn size(self) -> usize {
        match self {
            NpyDtype::F32 => 4,
            NpyDtype::F64 => 8,
        }
    }
}

/// Why bytes are not an `.npy` array this module reads (no path: [`crate::FieldIoError`] adds it).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum NpyError {
    /// The file does not start with `\x93NUMPY`.
    #[error("not an .npy file (missing the \\x93NUMPY magic)")]
    NotNpy,
    /// A format version other than 1.0, 2.0, 3.0.
    #[error("unsupported .npy format version {major}.{minor}")]
    Version {
        /// Major version byte.
        major: u8,
        /// Minor version byte.
        minor: u8,
    },
    /// The file ends inside the header or the data.
    #[error("truncated .npy file: {0}")]
    Truncated(String),
    /// The header dict cannot be parsed.
    #[error("malformed .npy header: {0}")]
    Header(String),
    /// A dtype that is not a float or an integer.
    #[error(
        "unsupported dtype {0:?} (only float32/float64 'f4'/'f8' and integers 'i1'…'i8', 'u1'…'u8', either byte order)"
    )]
    Dtype(String),
    /// An integer that `f64` cannot represent exactly (beyond ±2⁵³).
    #[error("element {index} ({value}, dtype {dtype:?}) cannot be represented exactly as float64")]
    Unrepresentable {
        /// Position of the element in the file's order.
        index: usize,
        /// The integer.
        value: String,
        /// The file's dtype.
        dtype: String,
    },
    /// The data section is longer than the shape says.
    #[error(
        "{extra}{} bytes of trailing data after the array",
        if *more { " or more" } else { "" }
    )]
    TrailingData {
        /// Number of unexpected bytes (a lower bound if `more`).
        extra: u64,
        /// Whether there are more than `extra` (a stream that was not read to its end).
        more: bool,
    },
}

/// A dense array of numbers read from or written to `.npy`, in C (row-major) order.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyArray {
    /// The shape, e.g. `[F, 3]`; an empty shape is a scalar (one element).
    pub shape: Vec<usize>,
    /// The elements in C order (`shape.iter().product()` of them), as `f64`.
    pub data: Vec<f64>,
    /// The element type to be written; read: [`NpyDtype::F32`] for a float32 file,
    /// [`NpyDtype::F64`] for every other (float64 or integer) one.
    pub dtype: NpyDtype,
}

/// Longest `.npy` header accepted (numpy writes a few hundred bytes at most).
pub const MAX_HEADER_BYTES: usize = 1 << 20;

/// What the header of an `.npy` file says: parsed by `npyz`, with the element type checked and
/// the data length computed.
struct Head {
    header: NpyHeader,
    element: Element,
    /// Where the data start (bytes from the file's start).
    data_start: usize,
    /// Number of elements.
    count: usize,
    /// Length of the data (bytes).
    needed: usize,
}

/// The element types read, by kind and size (either byte order).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Element {
    Float(usize),
    Int(usize),
    Uint(usize),
}

impl NpyArray {
    /// Where the data of an `.npy` file starts, read from its first bytes (magic, version,
    /// header length: 10 or 12 bytes); `None` if `prefix` is too short to tell. Headers longer
    /// than [`MAX_HEADER_BYTES`] are refused.
    pub fn data_start(prefix: &[u8]) -> Result<Option<usize>, NpyError> {
        if prefix.len() < 8 {
            return if MAGIC.starts_with(prefix) || prefix.starts_with(MAGIC) {
                Ok(None)
            } else {
                Err(NpyError::NotNpy)
            };
        }
        if &prefix[..6] != MAGIC {
            return Err(NpyError::NotNpy);
        }
        let (major, minor) = (prefix[6], prefix[7]);
        let length_size = match (major, minor) {
            (1, 0) => 2,
            (2, 0) | (3, 0) => 4,
            _ => return Err(NpyError::Version { major, minor }),
        };
        let start = 8 + length_size;
        if prefix.len() < start {
            return Ok(None);
        }
        let header_len = if length_size == 2 {
            u16::from_le_bytes([prefix[8], prefix[9]]) as usize
        } else {
            u32::from_le_bytes([prefix[8], prefix[9], prefix[10], prefix[11]]) as usize
        };
        if header_len > MAX_HEADER_BYTES {
            return Err(NpyError::Header(format!(
                "a header of {header_len} bytes is longer than any array needs ({MAX_HEADER_BYTES})"
            )));
        }
        Ok(Some(start + header_len))
    }

    /// Parses the bytes of an `.npy` file.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, NpyError> {
        let head = parse_head(bytes)?;
        let payload = &bytes[head.data_start..];
        if payload.len() < head.needed {
            return Err(NpyError::Truncated(format!(
                "shape {:?} needs {} data bytes, only {} present",
                head.header.shape(),
                head.needed,
                payload.len()
            )));
        }
        if payload.len() > head.needed {
            return Err(NpyError::TrailingData {
                extra: (payload.len() - head.needed) as u64,
                more: false,
            });
        }
        let descr = head.header.dtype().descr();
        let file = NpyFile::with_header(head.header.clone(), payload);
        let data = match head.element {
            Element::Float(4) => widened(read_all::<f32>(file)?),
            Element::Float(_) => read_all::<f64>(file)?,
            Element::Int(1) => widened(read_all::<i8>(file)?),
            Element::Int(2) => widened(read_all::<i16>(file)?),
            Element::Int(4) => widened(read_all::<i32>(file)?),
            Element::Int(_) => exactly(read_all::<i64>(file)?, &descr)?,
            Element::Uint(1) => widened(read_all::<u8>(file)?),
            Element::Uint(2) => widened(read_all::<u16>(file)?),
            Element::Uint(4) => widened(read_all::<u32>(file)?),
            Element::Uint(_) => exactly(read_all::<u64>(file)?, &descr)?,
        };
        if data.len() != head.count {
            return Err(NpyError::Truncated(format!(
                "{} of {} elements decoded",
                data.len(),
                head.count
            )));
        }
        let shape: Vec<usize> = head.header.shape().iter().map(|&d| d as usize).collect();
        let data = match head.header.order() {
            Order::C => data,
            Order::Fortran => fortran_to_c(&data, &shape),
        };
        let dtype = if head.element == Element::Float(4) {
            NpyDtype::F32
        } else {
            NpyDtype::F64
        };
        Ok(Self { shape, data, dtype })
    }

    /// The data length (bytes) the header of an `.npy` file promises; `head` holds the file's
    /// bytes at least up to the end of the header.
    pub fn payload_length(head: &[u8]) -> Result<usize, NpyError> {
        parse_head(head).map(|head| head.needed)
    }

    /// The bytes of the `.npy` file (little-endian `dtype`, C order, format 1.0 unless the
    /// header needs more; the data start at a multiple of 64 bytes). `f32` output rounds each
    /// value to nearest.
    pub fn to_bytes(&self) -> Vec<u8> {
        let shape: Vec<u64> = self.shape.iter().map(|&d| d as u64).collect();
        match self.dtype {
            NpyDtype::F64 => npy_of(&shape, self.data.iter().copied()),
            NpyDtype::F32 => npy_of(&shape, self.data.iter().map(|&x| x as f32)),
        }
    }
}

/// The `.npy` bytes of `values` (little-endian, their default dtype) with shape `shape`.
///
/// Writing into memory cannot fail for these dtypes; a count that does not match the shape is
/// a caller's error (checked before, e.g. by `write_npy`) and gives the bytes written so far.
pub(crate) fn npy_of<T: npyz::AutoSerialize>(
    shape: &[u64],
    values: impl Iterator<Item = T>,
) -> Vec<u8> {
    let mut out = Vec::new();
    let written = npyz::WriteOptions::new()
        .default_dtype()
        .shape(shape)
        .writer(&mut out)
        .begin_nd()
        .and_then(|mut writer| {
            writer.extend(values)?;
            writer.finish()
        });
    debug_assert!(written.is_ok(), "in-memory .npy write: {written:?}");
    out
}

/// The header of the `.npy` bytes `bytes` (at least up to its end), its element type and data
/// length.
fn parse_head(bytes: &[u8]) -> Result<Head, NpyError> {
    let data_start = match NpyArray::data_start(bytes)? {
        Some(start) => start,
        None if bytes.len() < 8 => {
            return Err(NpyError::Truncated(
                "file ends inside the magic string".into(),
            ))
        }
        None => {
            return Err(NpyError::Truncated(
                "file ends inside the header length".into(),
            ))
        }
    };
    let start = if bytes[6] == 1 { 10 } else { 12 };
    if bytes.len() < data_start {
        return Err(NpyError::Truncated(format!(
            "header says {} bytes, only {} present",
            data_start - start,
            bytes.len() - start
        )));
    }
    let header = NpyHeader::from_reader(&bytes[..data_start])
        .map_err(|e| NpyError::Header(e.to_string()))?;
    let element = match header.dtype() {
        DType::Plain(type_str) => element(&type_str)?,
        other => return Err(NpyError::Dtype(other.descr())),
    };
    let count = header
        .shape()
        .iter()
        .try_fold(1usize, |acc, &d| acc.checked_mul(usize::try_from(d).ok()?))
        .ok_or_else(|| NpyError::Header("shape overflows".into()))?;
    let size = match element {
        Element::Float(size) | Element::Int(size) | Element::Uint(size) => size,
    };
    let needed = count
        .checked_mul(size)
        .ok_or_else(|| NpyError::Header("shape overflows".into()))?;
    Ok(Head {
        header,
        element,
        data_start,
        count,
        needed,
    })
}

/// The element type of a plain dtype, if it is one this module reads.
fn element(type_str: &TypeStr) -> Result<Element, NpyError> {
    let size = type_str.size_field();
    match (type_str.type_char(), size) {
        (TypeChar::Float, 4 | 8) => Ok(Element::Float(size as usize)),
        (TypeChar::Int, 1 | 2 | 4 | 8) => Ok(Element::Int(size as usize)),
        (TypeChar::Uint, 1 | 2 | 4 | 8) => Ok(Element::Uint(size as usize)),
        _ => Err(NpyError::Dtype(type_str.to_string())),
    }
}

/// Every element of `file`'s data, in the file's order.
fn read_all<T: Deserialize>(file: NpyFile<&[u8]>) -> Result<Vec<T>, NpyError> {
    file.into_vec::<T>()
        .map_err(|e| NpyError::Truncated(e.to_string()))
}

/// Values that `f64` holds exactly (floats, integers of at most 32 bits) as `f64`.
fn widened<T: Into<f64>>(values: Vec<T>) -> Vec<f64> {
    values.into_iter().map(Into::into).collect()
}

/// 64-bit integers as `f64`, refusing any that `f64` cannot represent exactly.
fn exactly<T: Copy + Into<i128> + std::fmt::Display>(
    values: Vec<T>,
    descr: &str,
) -> Result<Vec<f64>, NpyError> {
    values
        .into_iter()
        .enumerate()
        .map(|(index, value)| {
            let wide: i128 = value.into();
            let x = wide as f64;
            if x as i128 == wide {
                Ok(x)
            } else {
                Err(NpyError::Unrepresentable {
                    index,
                    value: value.to_string(),
                    dtype: descr.trim_matches('\'').to_string(),
                })
            }
        })
        .collect()
}

/// The elements of an array of shape `shape` stored in Fortran (column-major) order, put in C
/// (row-major) order.
fn fortran_to_c(data: &[f64], shape: &[usize]) -> Vec<f64> {
    let mut fortran_strides = Vec::with_capacity(shape.len());
    let mut stride = 1usize;
    for &d in shape {
        fortran_strides.push(stride);
        stride *= d;
    }
    (0..data.len())
        .map(|c_index| {
            // Digits of the C index, last axis fastest, mapped to the Fortran position.
            let (mut rest, mut position) = (c_index, 0);
            for (&d, &s) in shape.iter().zip(&fortran_strides).rev() {
                position += (rest % d) * s;
                rest /= d;
            }
            data[position]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_f64_and_f32() {
        for dtype in [NpyDtype::F64, NpyDtype::F32] {
            let array = NpyArray {
                shape: vec![2, 3],
                data: vec![1.0, -2.5, 3.25, 0.0, 1e-3, 7.0],
                dtype,
            };
            let bytes = array.to_bytes();
            assert_eq!((bytes.len() - 6 * dtype.size()) % 64, 0);
            let back = NpyArray::from_bytes(&bytes).unwrap();
            assert_eq!(back.shape, array.shape);
            assert_eq!(back.dtype, dtype);
            for (a, b) in back.data.iter().zip(&array.data) {
                let expected = match dtype {
                    NpyDtype::F32 => (*b as f32) as f64,
                    NpyDtype::F64 => *b,
                };
                assert_eq!(*a, expected);
            }
        }
    }

    /// An `.npy` file written by hand: magic, version 1.0, the header dict padded to 64 bytes,
    /// then `data` as is.
    fn npy_file(header: &str, data: &[u8]) -> Vec<u8> {
        let mut dict = header.as_bytes().to_vec();
        while !(10 + dict.len() + 1).is_multiple_of(64) {
            dict.push(b' ');
        }
        dict.push(b'\n');
        let mut out = MAGIC.to_vec();
        out.extend_from_slice(&[1, 0]);
        out.extend_from_slice(&(dict.len() as u16).to_le_bytes());
        out.extend(dict);
        out.extend_from_slice(data);
        out
    }

    #[test]
    fn reads_numpy_style_headers() {
        let data: Vec<u8> = [1.0f32, 2.0, 3.0, 4.0, 5.0, 6.0]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let a = NpyArray::from_bytes(&npy_file(
            "{\"shape\":(2, 3),\"fortran_order\":False,\"descr\":\"<f4\"}",
            &data,
        ))
        .unwrap();
        assert_eq!((a.shape, a.dtype), (vec![2, 3], NpyDtype::F32));
        let scalar = NpyArray::from_bytes(&npy_file(
            "{'descr': '<f8', 'fortran_order': False, 'shape': (), }",
            &2.5f64.to_le_bytes(),
        ))
        .unwrap();
        assert_eq!((scalar.shape, scalar.data), (vec![], vec![2.5]));
        for bad in [
            "{'descr': '<f8', 'shape': (1,)}",
            "{'descr': '<f8', 'fortran_order': False, 'shape': (a,)}",
        ] {
            assert!(matches!(
                NpyArray::from_bytes(&npy_file(bad, &[0; 8])),
                Err(NpyError::Header(_))
            ));
        }
    }

    #[test]
    fn fortran_order_is_read_in_c_order() {
        // The 2 × 3 array [[1, 2, 3], [4, 5, 6]] stored column by column.
        let data: Vec<u8> = [1.0f64, 4.0, 2.0, 5.0, 3.0, 6.0]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let header = "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }";
        let a = NpyArray::from_bytes(&npy_file(header, &data)).unwrap();
        assert_eq!(a.shape, vec![2, 3]);
        assert_eq!(a.data, vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        // Three axes: element (i, j, k) of shape (2, 2, 2) is stored at i + 2j + 4k.
        let values: Vec<f64> = (0..8).map(f64::from).collect();
        let stored: Vec<u8> = (0..8)
            .map(|f: usize| {
                let (i, j, k) = (f % 2, (f / 2) % 2, f / 4);
                values[4 * i + 2 * j + k]
            })
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let header = "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 2, 2), }";
        assert_eq!(
            NpyArray::from_bytes(&npy_file(header, &stored))
                .unwrap()
                .data,
            values
        );
    }

    #[test]
    fn big_endian_and_integer_dtypes_are_converted() {
        let big: Vec<u8> = [1.5f64, -2.0, 1e300]
            .iter()
            .flat_map(|x| x.to_be_bytes())
            .collect();
        let a = NpyArray::from_bytes(&npy_file(
            "{'descr': '>f8', 'fortran_order': False, 'shape': (3,), }",
            &big,
        ))
        .unwrap();
        assert_eq!((a.data, a.dtype), (vec![1.5, -2.0, 1e300], NpyDtype::F64));
        let big32: Vec<u8> = [0.25f32, 3.0]
            .iter()
            .flat_map(|x| x.to_be_bytes())
            .collect();
        let a = NpyArray::from_bytes(&npy_file(
            "{'descr': '>f4', 'fortran_order': False, 'shape': (2,), }",
            &big32,
        ))
        .unwrap();
        assert_eq!((a.data, a.dtype), (vec![0.25, 3.0], NpyDtype::F32));
        let ints: Vec<u8> = [-3i32, 7, 1 << 30]
            .iter()
            .flat_map(|x| x.to_be_bytes())
            .collect();
        let a = NpyArray::from_bytes(&npy_file(
            "{'descr': '>i4', 'fortran_order': False, 'shape': (3,), }",
            &ints,
        ))
        .unwrap();
        assert_eq!(a.data, vec![-3.0, 7.0, (1 << 30) as f64]);
        let bytes = [0u8, 200, 255];
        let a = NpyArray::from_bytes(&npy_file(
            "{'descr': '|u1', 'fortran_order': False, 'shape': (3,), }",
            &bytes,
        ))
        .unwrap();
        assert_eq!(a.data, vec![0.0, 200.0, 255.0]);
        let exact: Vec<u8> = [1i64 << 53, -(1i64 << 60), 42]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let a = NpyArray::from_bytes(&npy_file(
            "{'descr': '<i8', 'fortran_order': False, 'shape': (3,), }",
            &exact,
        ))
        .unwrap();
        assert_eq!(
            a.data,
            vec![(1i64 << 53) as f64, -((1i64 << 60) as f64), 42.0]
        );
    }

    #[test]
    fn integers_float64_cannot_hold_are_refused() {
        let values: Vec<u8> = [1u64, (1 << 53) + 1]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        assert_eq!(
            NpyArray::from_bytes(&npy_file(
                "{'descr': '<u8', 'fortran_order': False, 'shape': (2,), }",
                &values,
            )),
            Err(NpyError::Unrepresentable {
                index: 1,
                value: ((1u64 << 53) + 1).to_string(),
                dtype: "<u8".into(),
            })
        );
        let max: Vec<u8> = i64::MAX.to_le_bytes().to_vec();
        assert!(matches!(
            NpyArray::from_bytes(&npy_file(
                "{'descr': '<i8', 'fortran_order': False, 'shape': (1,), }",
                &max,
            )),
            Err(NpyError::Unrepresentable { index: 0, .. })
        ));
    }

    #[test]
    fn rejects_bad_files() {
        let good = NpyArray {
            shape: vec![1, 3],
            data: vec![1.0, 2.0, 3.0],
            dtype: NpyDtype::F64,
        }
        .to_bytes();
        assert_eq!(NpyArray::from_bytes(b"hello world"), Err(NpyError::NotNpy));
        assert!(matches!(
            NpyArray::from_bytes(&good[..good.len() - 1]),
            Err(NpyError::Truncated(_))
        ));
        let mut extra = good.clone();
        extra.push(0);
        assert_eq!(
            NpyArray::from_bytes(&extra),
            Err(NpyError::TrailingData {
                extra: 1,
                more: false
            })
        );
        for (descr, shown) in [("'|b1'", "|b1"), ("'<c16'", "<c16"), ("'<U3'", "<U3")] {
            let header = format!("{{'descr': {descr}, 'fortran_order': False, 'shape': (1,), }}");
            assert_eq!(
                NpyArray::from_bytes(&npy_file(&header, &[0; 16])),
                Err(NpyError::Dtype(shown.into())),
                "{descr}"
            );
        }
        let mut v9 = good;
        v9[6] = 9;
        assert_eq!(
            NpyArray::from_bytes(&v9),
            Err(NpyError::Version { major: 9, minor: 0 })
        );
    }
}
