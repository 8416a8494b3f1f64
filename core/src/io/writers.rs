//! Writers: OBJ (text) and PLY (binary little-endian), always written atomically.

use crate::mesh::Mesh;
use std::io::Write;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// A mesh could not be written.
#[derive(Debug, Error)]
pub enum SaveError {
    /// The extension is neither `obj` nor `ply`.
    #[error("{}: unknown output format (expected .obj or .ply)", path.display())]
    UnknownFormat {
        /// The requested output path.
        path: PathBuf,
    },
    /// Creating, writing or renaming the file failed.
    #[error("{}: cannot write: {source}", path.display())]
    Io {
        /// The requested output path.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
}

/// Writes `mesh` to `path` as OBJ or PLY, chosen by the extension (case-insensitive).
pub fn save_mesh<M: Mesh + ?Sized>(path: impl AsRef<Path>, mesh: &M) -> Result<(), SaveError> {
    let path = path.as_ref();
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => write_obj(path, mesh),
        Some("ply") => write_ply(path, mesh),
        _ => Err(SaveError::UnknownFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// Writes Wavefront OBJ: `v x y z` (shortest decimal that reads back to the same `f64`) and
/// 1-based `f i j k …` lines (one per face, polygons as polygons), vertex and face order kept.
pub fn write_obj<M: Mesh + ?Sized>(path: impl AsRef<Path>, mesh: &M) -> Result<(), SaveError> {
    let (positions, faces) = (mesh.positions(), mesh.face_corners());
    write_atomically(path.as_ref(), |out| {
        writeln!(
            out,
            "# tvf: {} vertices, {} faces",
            positions.len(),
            faces.face_count()
        )?;
        for p in positions {
            writeln!(out, "v {} {} {}", p[0], p[1], p[2])?;
        }
        for f in 0..faces.face_count() {
            write!(out, "f")?;
            for &v in faces.corners(f) {
                write!(out, " {}", v + 1)?;
            }
            writeln!(out)?;
        }
        Ok(())
    })
}

/// Writes binary little-endian PLY: `double x, y, z` per vertex and a `uchar`-counted `uint`
/// index list per face (`uint`-counted when a face has more than 255 corners).
pub fn write_ply<M: Mesh + ?Sized>(path: impl AsRef<Path>, mesh: &M) -> Result<(), SaveError> {
    let (positions, faces) = (mesh.positions(), mesh.face_corners());
    let wide = (0..faces.face_count()).any(|f| faces.corners(f).len() > 255);
    write_atomically(path.as_ref(), |out| {
        write!(
            out,
            "ply\nformat binary_little_endian 1.0\ncomment written by tvf\n\
             element vertex {}\nproperty double x\nproperty double y\nproperty double z\n\
             element face {}\nproperty list {} uint vertex_indices\nend_header\n",
            positions.len(),
            faces.face_count(),
            if wide { "uint" } else { "uchar" }
        )?;
        for p in positions {
            for x in p {
                out.write_all(&x.to_le_bytes())?;
            }
        }
        for f in 0..faces.face_count() {
            let corners = faces.corners(f);
            if wide {
                out.write_all(&(corners.len() as u32).to_le_bytes())?;
            } else {
                out.write_all(&[corners.len() as u8])?;
            }
            for &v in corners {
                let v = u32::try_from(v).map_err(|_| {
                    std::io::Error::new(
                        std::io::ErrorKind::InvalidInput,
                        "vertex index does not fit PLY's uint",
                    )
                })?;
                out.write_all(&v.to_le_bytes())?;
            }
        }
        Ok(())
    })
}

/// Writes through `fill` into a temporary file in the target's directory, then renames it over
/// `path`, so readers never see a half-written file ([`super::write_atomically`]).
fn write_atomically(
    path: &Path,
    fill: impl FnOnce(&mut super::AtomicWriter<'_>) -> std::io::Result<()>,
) -> Result<(), SaveError> {
    super::write_atomically(path, fill).map_err(|source| SaveError::Io {
        path: path.to_path_buf(),
        source,
    })
}
