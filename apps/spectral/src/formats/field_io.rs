//! Field files: one 3D vector per face, as `.npy` (`F × 3`, `f32` or `f64`) or as text
//! (`x y z` per line, `#` starts a comment), plus sequences (`F × 3 × T` `.npy`) and plain
//! `.npy` arrays of any shape.
//!
//! The format is chosen by the extension: `.npy` is NumPy, anything else is text. Every write is
//! atomic ([`tvf_core::io::write_atomically`]); every error names the file.
//!
//! Vectors in files are 3D and **pointwise** (one vector per face, in the mesh's coordinates).
//! [`read_tangent_field`] turns them into a tangent field of `2F` face-frame coefficients by
//! projecting each onto its face's plane, and reports the dropped normal components.

use crate::formats::npy::{NpyArray, NpyDtype, NpyError};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use thiserror::Error;
use tvf_core::discretization::{FieldSampling, TangentProjection};
use tvf_core::io::write_atomically;
use tvf_core::io::{read_at_most, read_exactly_at_most};

/// What can go wrong reading or writing a field file (every variant names the file).
#[derive(Debug, Error)]
pub enum FieldIoError {
    /// The operating system refused (missing file, permissions, disk full, ...).
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The `.npy` file is damaged or of a kind tvf does not read.
    #[error("{}: {source}", path.display())]
    Npy {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        source: NpyError,
    },
    /// The array has the wrong shape.
    #[error("{}: array of shape {found:?}, expected {expected}", path.display())]
    Shape {
        /// The file.
        path: PathBuf,
        /// The shape that was expected, in words (e.g. "(F, 3)").
        expected: String,
        /// The shape in the file.
        found: Vec<usize>,
    },
    /// A line of a text field file is not three numbers.
    #[error("{}, line {line}: {message}", path.display())]
    Text {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file holds a different number of vectors than the mesh has faces.
    #[error("{}: {found} vectors, but the mesh has {expected} faces", path.display())]
    FaceCount {
        /// The file.
        path: PathBuf,
        /// Faces of the mesh.
        expected: usize,
        /// Vectors in the file.
        found: usize,
    },
    /// A vector component is NaN or infinite.
    #[error("{}: vector {index} has a non-finite component", path.display())]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// Index of the first offending vector (face).
        index: usize,
    },
    /// A component too large for `f64` arithmetic (or NaN): its square, and so lengths and
    /// energies, would overflow. Components must be at most [`crate::MAX_FIELD_COMPONENT`].
    #[error(
        "{}: the vector of face {face} has a component of {value:e}: too large for f64 \
         arithmetic (lengths and energies overflow; components must be at most {max:e})",
        path.display(),
        max = crate::MAX_FIELD_COMPONENT
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The face.
        face: usize,
        /// The component.
        value: f64,
    },
    /// A field whose largest component is not zero but below [`crate::MIN_FIELD_COMPONENT`]:
    /// its squared lengths and energies underflow.
    #[error(
        "{}: the largest component of the field is {largest:e}: too small for f64 arithmetic \
         (squared lengths and energies underflow to zero; the largest component must be at \
         least {min:e} unless the field is zero: scale the field up)",
        path.display(),
        min = crate::MIN_FIELD_COMPONENT
    )]
    TooSmall {
        /// The file.
        path: PathBuf,
        /// The largest component.
        largest: f64,
    },
    /// A field to write with a component that is NaN, infinite or above
    /// [`crate::MAX_FIELD_COMPONENT`]: the file would be refused when read back.
    #[error(
        "{}: cannot write the field: the vector of face {face} has the component {value:e} \
         (a written field must be finite, with components at most {max:e})",
        path.display(),
        max = crate::MAX_FIELD_COMPONENT
    )]
    Unwritable {
        /// The file.
        path: PathBuf,
        /// The face.
        face: usize,
        /// The component.
        value: f64,
    },
    /// A frame folder without frame files.
    #[error("{}: the folder holds no .npy or .txt frame", path.display())]
    NoFrames {
        /// The folder.
        path: PathBuf,
    },
    /// A frame that cannot be turned into a tangent field of the discretization.
    #[error("{}: frame {frame}: {source}", path.display())]
    Frame {
        /// The file.
        path: PathBuf,
        /// The frame (0-based).
        frame: usize,
        /// Why.
        source: tvf_core::discretization::DiscretizationError,
    },
    /// The data to write are inconsistent (ragged frames, shape not matching the data).
    #[error("{}: cannot write: {message}", path.display())]
    Inconsistent {
        /// The file.
        path: PathBuf,
        /// What is inconsistent.
        message: String,
    },
}

/// How to store one vector per face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldFileFormat {
    /// NumPy `.npy`, `F × 3`, with the given element type.
    Npy(NpyDtype),
    /// Text, one `x y z` line per face (shortest decimal that round-trips each `f64`).
    Text,
}

impl FieldFileFormat {
    /// `.npy` (`f64`) for a path ending in `.npy` (any case), text otherwise.
    pub fn from_path(path: &Path) -> Self {
        if is_npy(path) {
            FieldFileFormat::Npy(NpyDtype::F64)
        } else {
            FieldFileFormat::Text
        }
    }
}

fn is_npy(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"))
}

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> FieldIoError + '_ {
    move |source| FieldIoError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Reads any `.npy` array of floats or integers (either byte order, C or Fortran order; values
/// as `f64` in C order, see [`NpyArray::from_bytes`]). No more bytes are read than the header
/// justifies (the header, the data its shape needs, one byte to detect trailing data), so a
/// stream that never ends is refused.
pub fn read_npy(path: &Path) -> Result<NpyArray, FieldIoError> {
    let npy_error = |source| FieldIoError::Npy {
        path: path.to_path_buf(),
        source,
    };
    let mut file = std::fs::File::open(path).map_err(io_error(path))?;
    let mut bytes = Vec::new();
    read_exactly_at_most(&mut file, 12, &mut bytes).map_err(io_error(path))?;
    if let Some(start) = NpyArray::data_start(&bytes).map_err(npy_error)? {
        let header = (start as u64).saturating_sub(bytes.len() as u64);
        read_exactly_at_most(&mut file, header, &mut bytes).map_err(io_error(path))?;
        if bytes.len() == start {
            let payload = NpyArray::payload_length(&bytes).map_err(npy_error)? as u64;
            read_exactly_at_most(&mut file, payload.saturating_add(1), &mut bytes)
                .map_err(io_error(path))?;
        }
    }
    match NpyArray::from_bytes(&bytes) {
        // One byte past the array was read to see that there is more: count all of it.
        Err(NpyError::TrailingData { .. }) => {
            Err(npy_error(trailing_data(&mut file, bytes.len() as u64 - 1)))
        }
        result => result.map_err(npy_error),
    }
}

/// The trailing data of an `.npy` file whose array ends at byte `end` and which was read to
/// `end + 1`: the exact count for a regular file, for a stream what follows up to a bound.
fn trailing_data(file: &mut std::fs::File, end: u64) -> NpyError {
    const STREAM_BOUND: u64 = 1 << 20;
    match file.metadata() {
        Ok(metadata) if metadata.is_file() => NpyError::TrailingData {
            extra: metadata.len().saturating_sub(end),
            more: false,
        },
        _ => {
            let mut rest = Vec::new();
            let _ = read_exactly_at_most(file, STREAM_BOUND, &mut rest);
            let extra = 1 + rest.len() as u64;
            NpyError::TrailingData {
                extra,
                more: rest.len() as u64 == STREAM_BOUND,
            }
        }
    }
}

/// Largest text field file accepted: about 13 million faces at 80 bytes per line.
pub const MAX_TEXT_FIELD_BYTES: u64 = 1 << 30;

/// Writes an `.npy` array atomically. Fails with [`FieldIoError::Inconsistent`] if the number of
/// elements does not match the shape.
pub fn write_npy(path: &Path, array: &NpyArray) -> Result<(), FieldIoError> {
    let count: usize = array.shape.iter().product();
    if count != array.data.len() {
        return Err(FieldIoError::Inconsistent {
            path: path.to_path_buf(),
            message: format!(
                "shape {:?} has {count} elements, data has {}",
                array.shape,
                array.data.len()
            ),
        });
    }
    write_atomically(path, |w| w.write_all(&array.to_bytes())).map_err(io_error(path))
}

/// Reads one 3D vector per face from `path` (`.npy` `F × 3` of `f32`/`f64`, or text). Rejects
/// non-finite components.
pub fn read_face_vectors(path: &Path) -> Result<Vec<[f64; 3]>, FieldIoError> {
    let vectors = if is_npy(path) {
        let array = read_npy(path)?;
        if array.shape.len() != 2 || array.shape[1] != 3 {
            return Err(FieldIoError::Shape {
                path: path.to_path_buf(),
                expected: "(F, 3): one 3D vector per face".into(),
                found: array.shape,
            });
        }
        array
            .data
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect()
    } else {
        let bytes = read_at_most(path, MAX_TEXT_FIELD_BYTES).map_err(io_error(path))?;
        let text = String::from_utf8(bytes).map_err(|_| {
            io_error(path)(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                "stream did not contain valid UTF-8",
            ))
        })?;
        // A byte-order mark some editors write before the first line is not part of it.
        parse_text(path, text.strip_prefix('\u{feff}').unwrap_or(&text))?
    };
    if let Some(index) = vectors
        .iter()
        .position(|v: &[f64; 3]| v.iter().any(|x| !x.is_finite()))
    {
        return Err(FieldIoError::NonFinite {
            path: path.to_path_buf(),
            index,
        });
    }
    Ok(vectors)
}

fn parse_text(path: &Path, text: &str) -> Result<Vec<[f64; 3]>, FieldIoError> {
    let mut vectors = Vec::new();
    for (number, raw) in text.lines().enumerate() {
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let error = |message: String| FieldIoError::Text {
            path: path.to_path_buf(),
            line: number + 1,
            message,
        };
        let tokens: Vec<&str> = content
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
            .collect();
        if tokens.len() != 3 {
            return Err(error(format!(
                "expected 3 numbers `x y z`, found {}",
                tokens.len()
            )));
        }
        let mut v = [0.0; 3];
        for (slot, token) in v.iter_mut().zip(&tokens) {
            *slot = token
                .parse()
                .map_err(|_| error(format!("{token:?} is not a number")))?;
        }
        vectors.push(v);
    }
    Ok(vectors)
}

/// Writes one 3D vector per face, in the format given by the extension (`.npy` → `f64`).
pub fn write_face_vectors(path: &Path, vectors: &[[f64; 3]]) -> Result<(), FieldIoError> {
    write_face_vectors_as(path, vectors, FieldFileFormat::from_path(path))
}

/// Refuses vectors that the readers would refuse (see [`FieldIoError::Unwritable`]).
fn check_writable(path: &Path, vectors: &[[f64; 3]]) -> Result<(), FieldIoError> {
    for (face, v) in vectors.iter().enumerate() {
        if let Some(&value) = v
            .iter()
            .find(|x| !x.is_finite() || x.abs() > crate::MAX_FIELD_COMPONENT)
        {
            return Err(FieldIoError::Unwritable {
                path: path.to_path_buf(),
                face,
                value,
            });
        }
    }
    Ok(())
}

/// Writes one 3D vector per face in an explicit format (atomic). Vectors with a NaN, infinite
/// or too large component ([`FieldIoError::Unwritable`]) are refused: nothing is written.
pub fn write_face_vectors_as(
    path: &Path,
    vectors: &[[f64; 3]],
    format: FieldFileFormat,
) -> Result<(), FieldIoError> {
    check_writable(path, vectors)?;
    match format {
        FieldFileFormat::Npy(dtype) => write_npy(
            path,
            &NpyArray {
                shape: vec![vectors.len(), 3],
                data: vectors.iter().flatten().copied().collect(),
                dtype,
            },
        ),
        FieldFileFormat::Text => {
            let mut text = String::with_capacity(vectors.len() * 64);
            text.push_str("# one 3D vector per face: x y z\n");
            for v in vectors {
                // `{}` on f64 prints the shortest decimal that parses back to the same bits.
                let _ = writeln!(text, "{} {} {}", v[0], v[1], v[2]);
            }
            write_atomically(path, |w| w.write_all(text.as_bytes())).map_err(io_error(path))
        }
    }
}

/// Reads a sequence of fields stored as one `.npy` array `F × 3 × T` (element `[t][c][k]` is
/// component `c` of face `t` in frame `k`). Returns `T` frames of `F` vectors.
pub fn read_face_vector_sequence(path: &Path) -> Result<Vec<Vec<[f64; 3]>>, FieldIoError> {
    let array = read_npy(path)?;
    if array.shape.len() != 3 || array.shape[1] != 3 {
        return Err(FieldIoError::Shape {
            path: path.to_path_buf(),
            expected: "(F, 3, T): T frames of one 3D vector per face".into(),
            found: array.shape,
        });
    }
    let (faces, frames) = (array.shape[0], array.shape[2]);
    if let Some(position) = array.data.iter().position(|x| !x.is_finite()) {
        return Err(FieldIoError::NonFinite {
            path: path.to_path_buf(),
            index: position / (3 * frames),
        });
    }
    Ok((0..frames)
        .map(|k| {
            (0..faces)
                .map(|t| std::array::from_fn(|c| array.data[(t * 3 + c) * frames + k]))
                .collect()
        })
        .collect())
}

/// Writes `T` frames of `F` vectors as one `.npy` array `F × 3 × T` (atomic). All frames must
/// have the same length; vectors are checked as by [`write_face_vectors_as`].
pub fn write_face_vector_sequence(
    path: &Path,
    frames: &[Vec<[f64; 3]>],
    dtype: NpyDtype,
) -> Result<(), FieldIoError> {
    for frame in frames {
        check_writable(path, frame)?;
    }
    let faces = frames.first().map_or(0, Vec::len);
    if let Some(k) = frames.iter().position(|f| f.len() != faces) {
        return Err(FieldIoError::Inconsistent {
            path: path.to_path_buf(),
            message: format!(
                "frame {k} has {} vectors, frame 0 has {faces}",
                frames[k].len()
            ),
        });
    }
    let count = frames.len();
    let mut data = vec![0.0; faces * 3 * count];
    for (k, frame) in frames.iter().enumerate() {
        for (t, v) in frame.iter().enumerate() {
            for c in 0..3 {
                data[(t * 3 + c) * count + k] = v[c];
            }
        }
    }
    write_npy(
        path,
        &NpyArray {
            shape: vec![faces, 3, count],
            data,
            dtype,
        },
    )
}

/// Reads a field file for a mesh (one 3D vector per face) and turns it into a field of the
/// discretization whose sampling is `space` ([`FieldSampling::from_face_vectors`]).
///
/// Returns the field (`n1` coefficients) and the dropped normal
/// component of every vector (`F` entries, see [`TangentProjection`]). Fails with
/// [`FieldIoError::FaceCount`] if the file does not hold exactly one vector per face.
pub fn read_tangent_field<S: FieldSampling + ?Sized>(
    path: &Path,
    space: &S,
) -> Result<TangentProjection, FieldIoError> {
    let vectors = read_face_vectors(path)?;
    if vectors.len() != space.face_count() {
        return Err(FieldIoError::FaceCount {
            path: path.to_path_buf(),
            expected: space.face_count(),
            found: vectors.len(),
        });
    }
    space
        .from_face_vectors(&vectors)
        .map_err(|e| FieldIoError::Inconsistent {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
}

/// Writes a field (`n1` coefficients of the discretization whose sampling is `space`) as one 3D
/// vector per face, sampled at the centroids, format by extension.
pub fn write_tangent_field<S: FieldSampling + ?Sized>(
    path: &Path,
    space: &S,
    field: &[f64],
) -> Result<(), FieldIoError> {
    let vectors = space
        .to_face_vectors(field)
        .map_err(|e| FieldIoError::Inconsistent {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    write_face_vectors(path, &vectors)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_parsing_skips_comments_and_reports_lines() {
        let path = Path::new("f.txt");
        let v = parse_text(path, "# header\n1 2 3\n\n4,5,6 # trailing\n  -1e-3\t0 7\n").unwrap();
        assert_eq!(v, vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [-1e-3, 0.0, 7.0]]);
        let error = parse_text(path, "1 2 3\n1 2\n").unwrap_err();
        assert!(matches!(error, FieldIoError::Text { line: 2, .. }));
        assert!(error.to_string().contains("f.txt, line 2"));
        let error = parse_text(path, "1 2 x\n").unwrap_err();
        assert!(error.to_string().contains("\"x\" is not a number"));
    }
}
