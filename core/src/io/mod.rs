//! Reading and writing triangle meshes: OBJ, OFF and PLY in, OBJ and PLY out; and how every tvf
//! output is written: atomically ([`write_atomically`], [`StagedFolder`] for folders), after
//! [`check_output`], with interrupted and stale temporaries cleaned up ([`temporaries`]).
//!
//! Every reader goes through [`crate::TriangleMesh::validated`], so a [`LoadedMesh`] is always a
//! valid oriented manifold mesh, and a [`LoadError`] names the file, the line where one applies,
//! and the problem ([`LoadErrorKind`]).
//!
//! ```
//! use tvf_core::io::{parse_mesh_bytes, MeshFormat};
//! let text = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
//! let loaded = parse_mesh_bytes(text, MeshFormat::Obj, "tetrahedron.obj").unwrap();
//! assert_eq!(loaded.mesh.face_count(), 4);
//! assert!(loaded.mesh.is_closed());
//! assert!(loaded.report.warnings.is_empty());
//! ```

mod atomic_write;
mod bounded_read;
mod early_writeback;
mod error;
mod obj_reader;
mod off_reader;
mod output_path;
mod ply_header;
mod ply_reader;
mod raw_mesh;
mod staged_file;
mod staged_folder;
pub mod temporaries;
mod text;
mod write_faults;
mod writers;

pub use atomic_write::{write_atomically, AtomicWriter};
pub use bounded_read::{read_at_most, read_exactly_at_most};
pub use early_writeback::EarlyWriteback;
pub use error::{LoadError, LoadErrorKind};
pub use output_path::{check_file_output, check_output, OutputPathError};
pub use raw_mesh::LoadedMesh;
pub use staged_file::StagedFile;
pub use staged_folder::StagedFolder;
pub use write_faults::{inject_write_faults, WriteFault, WriteFaultHook, STALL};
pub use writers::{save_mesh, write_obj, write_ply, SaveError};

use std::path::Path;

/// The file formats tvf reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (text).
    Obj,
    /// Object File Format (text).
    Off,
    /// Stanford PLY (ASCII or binary, little- or big-endian).
    Ply,
}

impl MeshFormat {
    /// The format for a file extension (case-insensitive), if tvf reads it.
    pub fn from_extension(extension: &str) -> Option<Self> {
        match extension.to_ascii_lowercase().as_str() {
            "obj" => Some(Self::Obj),
            "off" => Some(Self::Off),
            "ply" => Some(Self::Ply),
            _ => None,
        }
    }
}

/// Reads, parses and validates the mesh at `path`; the format is chosen by the extension.
pub fn load_mesh(path: impl AsRef<Path>) -> Result<LoadedMesh, LoadError> {
    let path = path.as_ref();
    let error = |kind| LoadError {
        path: path.to_path_buf(),
        line: None,
        kind,
    };
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let format = MeshFormat::from_extension(extension).ok_or_else(|| {
        error(LoadErrorKind::UnknownFormat {
            extension: extension.to_string(),
        })
    })?;
    // A regular file is read whole (its size bounds it); a stream (a FIFO, a device) only up
    // to MAX_STREAMED_MESH_BYTES, so one that never ends is refused.
    let limit = match std::fs::metadata(path) {
        Ok(m) if m.is_file() => u64::MAX,
        _ => MAX_STREAMED_MESH_BYTES,
    };
    let bytes = read_at_most(path, limit).map_err(|e| {
        error(LoadErrorKind::Unreadable {
            reason: e.to_string(),
        })
    })?;
    parse_mesh_bytes(&bytes, format, path)
}

/// Most bytes read from a mesh that is not a regular file (a FIFO, a device): 1 GiB, about ten
/// million faces of text.
pub const MAX_STREAMED_MESH_BYTES: u64 = 1 << 30;

/// The UTF-8 byte-order mark some editors put at the start of a text file.
pub const UTF8_BOM: &[u8] = b"\xEF\xBB\xBF";

/// Parses and validates a mesh held in memory; `name` is used in errors in place of a path. A
/// leading UTF-8 byte-order mark is skipped (in every format: the PLY header is text too).
pub fn parse_mesh_bytes(
    bytes: &[u8],
    format: MeshFormat,
    name: impl AsRef<Path>,
) -> Result<LoadedMesh, LoadError> {
    let name = name.as_ref();
    let bytes = bytes.strip_prefix(UTF8_BOM).unwrap_or(bytes);
    let raw = match format {
        MeshFormat::Obj => text::as_text(bytes).and_then(|text| obj_reader::read_obj(&text)),
        MeshFormat::Off => text::as_text(bytes).and_then(|text| off_reader::read_off(&text)),
        MeshFormat::Ply => ply_reader::read_ply(bytes),
    };
    match raw {
        Ok(raw) => raw.into_loaded(name),
        Err((line, kind)) => Err(LoadError {
            path: name.to_path_buf(),
            line,
            kind,
        }),
    }
}
