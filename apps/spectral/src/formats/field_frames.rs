//! Fields and sequences of fields (frames) in files, as tangent fields of a discretization: one
//! field file, an `.npy` array `F × 3 × T`, or a folder of field files (one per frame, in
//! file-name order). Reading projects every vector onto its face's plane and refuses
//! components too large for `f64` arithmetic; writing is atomic (a folder appears whole or not
//! at all).

use crate::{
    read_face_vector_sequence, read_tangent_field, write_face_vector_sequence, write_tangent_field,
    FieldIoError, NpyDtype,
};
use std::path::{Path, PathBuf};
use tvf_core::discretization::FieldSampling;
use tvf_core::io::StagedFolder;

/// Largest accepted field component: its square (and a sum of a few of them) stays finite, so
/// magnitudes and energies of the field can be computed in `f64`.
pub const MAX_FIELD_COMPONENT: f64 = 1e150;

/// Smallest accepted largest component of a field that is not zero: below it, squared lengths
/// and energies underflow to zero (or lose their digits), so every norm, share and relative
/// error of the field would be wrong.
pub const MIN_FIELD_COMPONENT: f64 = 1e-150;

/// One field read from a file.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldFromFile {
    /// The tangent field (`n1` coefficients).
    pub field: Vec<f64>,
    /// The largest dropped normal component (units of the field; 0 for tangent input).
    pub max_normal_part: f64,
}

/// Where a sequence of frames came from (and how it is written back by default).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameSource {
    /// One field file.
    Single,
    /// One `.npy` array `F × 3 × T`.
    Array,
    /// A folder of field files, one per frame, in file-name order.
    Folder,
}

/// Frames read from a file or folder.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldFrames {
    /// The tangent fields (`n1` coefficients each), in order.
    pub frames: Vec<Vec<f64>>,
    /// What the input was.
    pub source: FrameSource,
    /// The largest dropped normal component over all frames.
    pub max_normal_part: f64,
}

impl FieldFromFile {
    /// What to tell the user about the normal components dropped from the file `path`, if
    /// any were ([`dropped_normal_note`]).
    pub fn dropped_normal_note(&self, path: &Path) -> Option<String> {
        dropped_normal_note(path, self.max_normal_part)
    }
}

impl FieldFrames {
    /// What to tell the user about the normal components dropped from the frames of `path`,
    /// if any were ([`dropped_normal_note`]).
    pub fn dropped_normal_note(&self, path: &Path) -> Option<String> {
        dropped_normal_note(path, self.max_normal_part)
    }
}

/// `PATH: normal components up to N were dropped (fields are tangent)` when the largest
/// dropped normal component `max_normal_part` of the input `path` is not zero.
fn dropped_normal_note(path: &Path, max_normal_part: f64) -> Option<String> {
    (max_normal_part > 0.0).then(|| {
        format!(
            "{}: normal components up to {max_normal_part:.3e} were dropped (fields are tangent)",
            path.display()
        )
    })
}

/// Reads one field file (`.npy` `F × 3` or text) as a tangent field of `sampling`.
pub fn read_field_file(
    path: &Path,
    sampling: &dyn FieldSampling,
) -> Result<FieldFromFile, FieldIoError> {
    let projection = read_tangent_field(path, sampling)?;
    check_magnitudes(path, &projection.field)?;
    Ok(FieldFromFile {
        max_normal_part: projection.max_normal_part(),
        field: projection.field,
    })
}

/// Refuses a field with a NaN component or one above [`MAX_FIELD_COMPONENT`], and a field
/// that is not zero but whose largest component is below [`MIN_FIELD_COMPONENT`].
fn check_magnitudes(path: &Path, field: &[f64]) -> Result<(), FieldIoError> {
    if let Some((k, &value)) = field
        .iter()
        .enumerate()
        .find(|(_, x)| x.is_nan() || x.abs() > MAX_FIELD_COMPONENT)
    {
        return Err(FieldIoError::TooLarge {
            path: path.to_path_buf(),
            face: k / 2,
            value,
        });
    }
    let largest = field.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if largest > 0.0 && largest < MIN_FIELD_COMPONENT {
        return Err(FieldIoError::TooSmall {
            path: path.to_path_buf(),
            largest,
        });
    }
    Ok(())
}

/// Reads a field or a sequence: a folder of field files (`.npy` or `.txt`, sorted by name), an
/// `.npy` array `F × 3 × T`, or one field file.
pub fn read_field_frames(
    path: &Path,
    sampling: &dyn FieldSampling,
) -> Result<FieldFrames, FieldIoError> {
    let io = |source| FieldIoError::Io {
        path: path.to_path_buf(),
        source,
    };
    if path.is_dir() {
        let mut files: Vec<PathBuf> = std::fs::read_dir(path)
            .map_err(io)?
            .filter_map(|entry| entry.ok().map(|e| e.path()))
            .filter(|p| {
                p.is_file() && matches!(p.extension().and_then(|e| e.to_str()), Some("npy" | "txt"))
            })
            .collect();
        files.sort();
        if files.is_empty() {
            return Err(FieldIoError::NoFrames {
                path: path.to_path_buf(),
            });
        }
        let fields = files
            .iter()
            .map(|file| read_field_file(file, sampling))
            .collect::<Result<Vec<_>, _>>()?;
        return Ok(FieldFrames {
            max_normal_part: fields.iter().map(|f| f.max_normal_part).fold(0.0, f64::max),
            frames: fields.into_iter().map(|f| f.field).collect(),
            source: FrameSource::Folder,
        });
    }
    let is_npy = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
    if is_npy {
        match read_face_vector_sequence(path) {
            Ok(sequence) => {
                let mut frames = Vec::with_capacity(sequence.len());
                let mut max_normal_part = 0.0f64;
                for (frame, vectors) in sequence.iter().enumerate() {
                    if vectors.len() != sampling.face_count() {
                        return Err(FieldIoError::FaceCount {
                            path: path.to_path_buf(),
                            found: vectors.len(),
                            expected: sampling.face_count(),
                        });
                    }
                    let projection = sampling.from_face_vectors(vectors).map_err(|source| {
                        FieldIoError::Frame {
                            path: path.to_path_buf(),
                            frame,
                            source,
                        }
                    })?;
                    check_magnitudes(path, &projection.field)?;
                    max_normal_part = max_normal_part.max(projection.max_normal_part());
                    frames.push(projection.field);
                }
                return Ok(FieldFrames {
                    frames,
                    source: FrameSource::Array,
                    max_normal_part,
                });
            }
            Err(FieldIoError::Shape { found, .. }) if found.len() == 2 => {}
            Err(error) => return Err(error),
        }
    }
    let single = read_field_file(path, sampling)?;
    Ok(FieldFrames {
        frames: vec![single.field],
        source: FrameSource::Single,
        max_normal_part: single.max_normal_part,
    })
}

/// Writes frames of `sampling`: one frame to the file `out` (format by extension); several to
/// one `.npy` array `F × 3 × T` if `out` ends in `.npy`, otherwise into the folder `out` as
/// `frame_00000.npy`, `frame_00001.npy`, ... (staged, so the folder appears whole or not at
/// all).
pub fn write_field_frames(
    out: &Path,
    sampling: &dyn FieldSampling,
    frames: &[Vec<f64>],
) -> Result<(), FieldIoError> {
    if let [single] = frames {
        return write_tangent_field(out, sampling, single);
    }
    let inconsistent = |message: String| FieldIoError::Inconsistent {
        path: out.to_path_buf(),
        message,
    };
    let vectors = frames
        .iter()
        .map(|f| sampling.to_face_vectors(f))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| inconsistent(e.to_string()))?;
    if out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"))
    {
        return write_face_vector_sequence(out, &vectors, NpyDtype::F64);
    }
    let io = |source| FieldIoError::Io {
        path: out.to_path_buf(),
        source,
    };
    let staged = StagedFolder::new(out).map_err(io)?;
    for (k, frame) in frames.iter().enumerate() {
        write_tangent_field(
            &staged.path().join(format!("frame_{k:05}.npy")),
            sampling,
            frame,
        )?;
    }
    staged.commit().map_err(io)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dropped_normal_components_are_noted_only_when_there_were_some() {
        let read = FieldFromFile {
            field: vec![0.0; 2],
            max_normal_part: 0.25,
        };
        assert_eq!(
            read.dropped_normal_note(Path::new("f.npy")).as_deref(),
            Some("f.npy: normal components up to 2.500e-1 were dropped (fields are tangent)")
        );
        let frames = FieldFrames {
            frames: vec![vec![0.0; 2]],
            source: FrameSource::Single,
            max_normal_part: 0.0,
        };
        assert_eq!(frames.dropped_normal_note(Path::new("f.npy")), None);
    }
}
