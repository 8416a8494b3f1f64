//! NumPy `.npy` arrays of floating point numbers (format versions 1.0, 2.0 and 3.0).
//!
//! Only what tangent fields need: little-endian `f32` (`<f4`) or `f64` (`<f8`) data in C order,
//! any number of dimensions. The header is parsed as the Python dict literal the format
//! specifies (`{'descr': '<f8', 'fortran_order': False, 'shape': (F, 3), }`), so keys may come
//! in any order and with any spacing. Everything else (Fortran order, big-endian or integer
//! dtypes, object arrays, truncated data) is rejected with a [`NpyError`] saying why.

use thiserror::Error;

/// The magic string every `.npy` file starts with.
const MAGIC: &[u8; 6] = b"\x93NUMPY";

/// Element type of an `.npy` array.
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
    /// A dtype other than little-endian `f4`/`f8`.
    #[error("unsupported dtype {0:?} (only little-endian float32 '<f4' and float64 '<f8')")]
    Dtype(String),
    /// `fortran_order: True`.
    #[error(
        "Fortran-order arrays are not supported (save with C order, e.g. np.ascontiguousarray)"
    )]
    FortranOrder,
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

/// A dense floating point array read from or written to `.npy`, in C (row-major) order.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyArray {
    /// The shape, e.g. `[F, 3]`; an empty shape is a scalar (one element).
    pub shape: Vec<usize>,
    /// The elements in C order (`shape.iter().product()` of them), widened to `f64`.
    pub data: Vec<f64>,
    /// The element type found in (or to be written to) the file.
    pub dtype: NpyDtype,
}

/// Longest `.npy` header accepted (numpy writes a few hundred bytes at most).
pub const MAX_HEADER_BYTES: usize = 1 << 20;

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
        let (parsed, dtype, data_start, needed) = Self::parse_head(bytes)?;
        let payload = &bytes[data_start..];
        if payload.len() < needed {
            return Err(NpyError::Truncated(format!(
                "shape {:?} needs {needed} data bytes, only {} present",
                parsed.shape,
                payload.len()
            )));
        }
        if payload.len() > needed {
            return Err(NpyError::TrailingData {
                extra: (payload.len() - needed) as u64,
                more: false,
            });
        }
        let data = match dtype {
            NpyDtype::F64 => payload
                .chunks_exact(8)
                .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
                .collect(),
            NpyDtype::F32 => payload
                .chunks_exact(4)
                .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64)
                .collect(),
        };
        Ok(Self {
            shape: parsed.shape,
            data,
            dtype,
        })
    }

    /// The data length (bytes) the header of an `.npy` file promises; `head` holds the file's
    /// bytes at least up to the end of the header.
    pub fn payload_length(head: &[u8]) -> Result<usize, NpyError> {
        Self::parse_head(head).map(|(_, _, _, needed)| needed)
    }

    /// Header, dtype, data start and data length of the `.npy` bytes `bytes` (at least up to the
    /// end of the header).
    fn parse_head(bytes: &[u8]) -> Result<(Header, NpyDtype, usize, usize), NpyError> {
        let data_start = match Self::data_start(bytes)? {
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
        let utf8 = bytes[6] == 3;
        let start = if bytes[6] == 1 { 10 } else { 12 };
        if bytes.len() < data_start {
            return Err(NpyError::Truncated(format!(
                "header says {} bytes, only {} present",
                data_start - start,
                bytes.len() - start
            )));
        }
        let header_bytes = &bytes[start..data_start];
        let header = if utf8 {
            std::str::from_utf8(header_bytes).map_err(|_| NpyError::Header("not UTF-8".into()))?
        } else {
            if !header_bytes.is_ascii() {
                return Err(NpyError::Header("not ASCII".into()));
            }
            std::str::from_utf8(header_bytes).map_err(|_| NpyError::Header("not ASCII".into()))?
        };
        let parsed = parse_header(header)?;
        let dtype = match parsed.descr.as_str() {
            "<f8" => NpyDtype::F64,
            "<f4" => NpyDtype::F32,
            other => return Err(NpyError::Dtype(other.to_string())),
        };
        if parsed.fortran_order {
            return Err(NpyError::FortranOrder);
        }
        let count = parsed
            .shape
            .iter()
            .try_fold(1usize, |acc, &d| acc.checked_mul(d))
            .ok_or_else(|| NpyError::Header("shape overflows".into()))?;
        let needed = count
            .checked_mul(dtype.size())
            .ok_or_else(|| NpyError::Header("shape overflows".into()))?;
        Ok((parsed, dtype, data_start, needed))
    }

    /// The bytes of the `.npy` file ([`npy_header`], then the data). `f32` output rounds each
    /// value to nearest.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = npy_header(self.dtype.descr(), &self.shape);
        out.reserve(self.data.len() * self.dtype.size());
        match self.dtype {
            NpyDtype::F64 => self
                .data
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            NpyDtype::F32 => self
                .data
                .iter()
                .for_each(|&x| out.extend_from_slice(&(x as f32).to_le_bytes())),
        }
        out
    }
}

/// The header of an `.npy` file whose C-order data of element type `descr` (e.g. `<f8`) and
/// shape `shape` follows it: magic, format version (1.0 unless the header needs 2.0), header
/// length, and the header dict padded with spaces and a newline so that the data starts at a
/// multiple of 64 bytes.
pub(crate) fn npy_header(descr: &str, shape: &[usize]) -> Vec<u8> {
    let shape = match shape {
        [n] => format!("({n},)"),
        dims => format!(
            "({})",
            dims.iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    // Total of magic + version + length field + dict + padding + '\n' is a multiple of 64.
    let unpadded_v1 = 10 + dict.len() + 1;
    let (version, length_size) = if unpadded_v1.div_ceil(64) * 64 - 10 <= u16::MAX as usize {
        (1u8, 2usize)
    } else {
        (2u8, 4usize)
    };
    let prefix = 8 + length_size;
    let total = (prefix + dict.len() + 1).div_ceil(64) * 64;
    let header_len = total - prefix;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&[version, 0]);
    if length_size == 2 {
        out.extend_from_slice(&(header_len as u16).to_le_bytes());
    } else {
        out.extend_from_slice(&(header_len as u32).to_le_bytes());
    }
    out.extend_from_slice(dict.as_bytes());
    out.resize(total - 1, b' ');
    out.push(b'\n');
    out
}

struct Header {
    descr: String,
    fortran_order: bool,
    shape: Vec<usize>,
}

/// Parses `{'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }` (keys in any order).
fn parse_header(text: &str) -> Result<Header, NpyError> {
    let mut p = Parser {
        s: text.as_bytes(),
        i: 0,
    };
    p.expect(b'{')?;
    let (mut descr, mut fortran, mut shape) = (None, None, None);
    loop {
        p.skip_space();
        if p.eat(b'}') {
            break;
        }
        let key = p.string()?;
        p.skip_space();
        p.expect(b':')?;
        p.skip_space();
        match key.as_str() {
            "descr" => descr = Some(p.string()?),
            "fortran_order" => fortran = Some(p.boolean()?),
            "shape" => shape = Some(p.tuple()?),
            other => return Err(NpyError::Header(format!("unknown key {other:?}"))),
        }
        p.skip_space();
        if !p.eat(b',') {
            p.skip_space();
            p.expect(b'}')?;
            break;
        }
    }
    p.skip_space();
    if p.i != p.s.len() {
        return Err(NpyError::Header("text after the closing brace".into()));
    }
    let missing = |k: &str| NpyError::Header(format!("missing key '{k}'"));
    Ok(Header {
        descr: descr.ok_or_else(|| missing("descr"))?,
        fortran_order: fortran.ok_or_else(|| missing("fortran_order"))?,
        shape: shape.ok_or_else(|| missing("shape"))?,
    })
}

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn skip_space(&mut self) {
        while self.i < self.s.len() && self.s[self.i].is_ascii_whitespace() {
            self.i += 1;
        }
    }

    fn eat(&mut self, c: u8) -> bool {
        if self.s.get(self.i) == Some(&c) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    fn expect(&mut self, c: u8) -> Result<(), NpyError> {
        if self.eat(c) {
            Ok(())
        } else {
            Err(NpyError::Header(format!(
                "expected '{}' at byte {}",
                c as char, self.i
            )))
        }
    }

    fn string(&mut self) -> Result<String, NpyError> {
        let quote = match self.s.get(self.i) {
            Some(&q @ (b'\'' | b'"')) => q,
            _ => {
                return Err(NpyError::Header(format!(
                    "expected a quoted string at byte {}",
                    self.i
                )))
            }
        };
        self.i += 1;
        let start = self.i;
        while self.i < self.s.len() && self.s[self.i] != quote {
            self.i += 1;
        }
        if self.i == self.s.len() {
            return Err(NpyError::Header("unterminated string".into()));
        }
        let value = String::from_utf8_lossy(&self.s[start..self.i]).into_owned();
        self.i += 1;
        Ok(value)
    }

    fn boolean(&mut self) -> Result<bool, NpyError> {
        let rest = &self.s[self.i..];
        if rest.starts_with(b"True") {
            self.i += 4;
            Ok(true)
        } else if rest.starts_with(b"False") {
            self.i += 5;
            Ok(false)
        } else {
            Err(NpyError::Header(
                "fortran_order must be True or False".into(),
            ))
        }
    }

    fn tuple(&mut self) -> Result<Vec<usize>, NpyError> {
        self.expect(b'(')?;
        let mut dims = Vec::new();
        loop {
            self.skip_space();
            if self.eat(b')') {
                return Ok(dims);
            }
            let start = self.i;
            while self.i < self.s.len() && self.s[self.i].is_ascii_digit() {
                self.i += 1;
            }
            // Python 2 era writers append 'L' to long integers.
            let digits = std::str::from_utf8(&self.s[start..self.i]).unwrap_or("");
            let value: usize = digits
                .parse()
                .map_err(|_| NpyError::Header(format!("bad dimension in shape at byte {start}")))?;
            self.eat(b'L');
            dims.push(value);
            self.skip_space();
            if !self.eat(b',') {
                self.skip_space();
                self.expect(b')')?;
                return Ok(dims);
            }
        }
    }
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

    #[test]
    fn parses_numpy_style_headers() {
        let header = "{'descr': '<f8', 'fortran_order': False, 'shape': (4,), }";
        let h = parse_header(header).unwrap();
        assert_eq!(h.shape, vec![4]);
        let h =
            parse_header("{\"shape\":(2L, 3L),\"fortran_order\":True,\"descr\":\"<f4\"}").unwrap();
        assert_eq!(h.shape, vec![2, 3]);
        assert!(h.fortran_order);
        assert_eq!(
            parse_header("{'descr': '<f8', 'fortran_order': False, 'shape': (), }")
                .unwrap()
                .shape,
            Vec::<usize>::new()
        );
        assert!(parse_header("{'descr': '<f8', 'shape': (1,)}").is_err());
        assert!(parse_header("{'descr': '<f8', 'fortran_order': False, 'shape': (a,)}").is_err());
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
        let mut fortran = good.clone();
        let pos = fortran.windows(5).position(|w| w == b"False").unwrap();
        fortran[pos..pos + 5].copy_from_slice(b"True ");
        assert_eq!(NpyArray::from_bytes(&fortran), Err(NpyError::FortranOrder));
        let mut big_endian = good.clone();
        let pos = big_endian.windows(3).position(|w| w == b"<f8").unwrap();
        big_endian[pos] = b'>';
        assert_eq!(
            NpyArray::from_bytes(&big_endian),
            Err(NpyError::Dtype(">f8".into()))
        );
        let mut v9 = good;
        v9[6] = 9;
        assert_eq!(
            NpyArray::from_bytes(&v9),
            Err(NpyError::Version { major: 9, minor: 0 })
        );
    }
}
