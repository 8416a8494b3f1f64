//! PLY (ASCII) export: vertices, faces, and per-face vectors and scalars as face
//! properties, for MeshLab and Polyscope.

use std::io::Write;
use std::path::Path;

use tvf_core::SurfaceMesh;

use super::atomic::write_atomically;
use super::{check_data, FaceData};
use crate::error::RenderError;

/// Writes `mesh` and `data` to `path` as ASCII PLY. Each face element carries
/// `list uchar int vertex_indices`, then for every vector field `name` the double
/// properties `name_x name_y name_z`, then one double property per scalar.
pub fn write_ply(path: &Path, mesh: &SurfaceMesh, data: &FaceData) -> Result<(), RenderError> {
    check_data(mesh, data, "PLY")?;
    write_atomically(path, |w| {
        writeln!(w, "ply")?;
        writeln!(w, "format ascii 1.0")?;
        writeln!(w, "comment written by tvf")?;
        writeln!(w, "element vertex {}", mesh.vertex_count())?;
        for c in ["x", "y", "z"] {
            writeln!(w, "property double {c}")?;
        }
        writeln!(w, "element face {}", mesh.face_count())?;
        let wide = (0..mesh.face_count()).any(|f| mesh.face_size(f) > 255);
        let count_type = if wide { "uint" } else { "uchar" };
        writeln!(w, "property list {count_type} int vertex_indices")?;
        for (name, _) in &data.vectors {
            for c in ["x", "y", "z"] {
                writeln!(w, "property double {name}_{c}")?;
            }
        }
        for (name, _) in &data.scalars {
            writeln!(w, "property double {name}")?;
        }
        writeln!(w, "end_header")?;
        for p in mesh.positions() {
            writeln!(w, "{} {} {}", p[0], p[1], p[2])?;
        }
        for t in 0..mesh.face_count() {
            write!(w, "{}", mesh.face_size(t))?;
            for v in mesh.face(t) {
                write!(w, " {v}")?;
            }
            for (_, values) in &data.vectors {
                let v = values[t];
                write!(w, " {} {} {}", v[0], v[1], v[2])?;
            }
            for (_, values) in &data.scalars {
                write!(w, " {}", values[t])?;
            }
            writeln!(w)?;
        }
        Ok(())
    })
}
