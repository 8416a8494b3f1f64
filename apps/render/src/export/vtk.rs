//! VTK legacy (ASCII POLYDATA) export: the mesh with per-face vectors and scalars as
//! CELL_DATA, for ParaView.

use std::io::Write;
use std::path::Path;

use tvf_core::SurfaceMesh;

use super::atomic::write_atomically;
use super::{check_data, FaceData};
use crate::error::RenderError;

/// Writes `mesh` and `data` to `path` as a VTK legacy ASCII file
/// (`DATASET POLYDATA`, `POINTS V double`, `POLYGONS F 4F`, `CELL_DATA F` with one
/// `VECTORS name double` per vector field and one `SCALARS name double 1` per scalar).
/// Names must be non-empty and contain no whitespace.
pub fn write_vtk(path: &Path, mesh: &SurfaceMesh, data: &FaceData) -> Result<(), RenderError> {
    check_data(mesh, data, "VTK")?;
    write_atomically(path, |w| {
        writeln!(w, "# vtk DataFile Version 3.0")?;
        writeln!(w, "tvf tangent field")?;
        writeln!(w, "ASCII")?;
        writeln!(w, "DATASET POLYDATA")?;
        writeln!(w, "POINTS {} double", mesh.vertex_count())?;
        for p in mesh.positions() {
            writeln!(w, "{} {} {}", p[0], p[1], p[2])?;
        }
        let corners: usize = (0..mesh.face_count()).map(|f| mesh.face_size(f)).sum();
        writeln!(
            w,
            "POLYGONS {} {}",
            mesh.face_count(),
            mesh.face_count() + corners
        )?;
        for f in 0..mesh.face_count() {
            write!(w, "{}", mesh.face_size(f))?;
            for v in mesh.face(f) {
                write!(w, " {v}")?;
            }
            writeln!(w)?;
        }
        if data.vectors.is_empty() && data.scalars.is_empty() {
            return Ok(());
        }
        writeln!(w, "CELL_DATA {}", mesh.face_count())?;
        for (name, values) in &data.vectors {
            writeln!(w, "VECTORS {name} double")?;
            for v in values {
                writeln!(w, "{} {} {}", v[0], v[1], v[2])?;
            }
        }
        for (name, values) in &data.scalars {
            writeln!(w, "SCALARS {name} double 1")?;
            writeln!(w, "LOOKUP_TABLE default")?;
            for v in values {
                writeln!(w, "{v}")?;
            }
        }
        Ok(())
    })
}
