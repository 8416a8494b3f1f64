//! OBJ export: the mesh (`v`, `f`) and polylines (`l`), e.g. streamlines or fur strands.

use std::io::Write;
use std::path::Path;

use tvf_core::SurfaceMesh;

use super::atomic::write_atomically;
use crate::error::RenderError;

/// Writes `mesh` (if given) and `polylines` to `path` as OBJ: mesh vertices first, then
/// the polyline points, faces as `f` and each polyline with at least two points as one
/// `l` line (1-based indices). Polylines with fewer than two points are skipped.
pub fn write_obj(
    path: &Path,
    mesh: Option<&SurfaceMesh>,
    polylines: &[Vec<[f64; 3]>],
) -> Result<(), RenderError> {
    if let Some((i, _)) = polylines
        .iter()
        .enumerate()
        .find(|(_, l)| l.iter().any(|p| p.iter().any(|x| !x.is_finite())))
    {
        return Err(RenderError::NonFinite {
            what: "polyline".into(),
            index: i,
        });
    }
    write_atomically(path, |w| {
        writeln!(w, "# written by tvf")?;
        let mut offset = 1;
        if let Some(mesh) = mesh {
            for p in mesh.positions() {
                writeln!(w, "v {} {} {}", p[0], p[1], p[2])?;
            }
            for f in 0..mesh.face_count() {
                write!(w, "f")?;
                for v in mesh.face(f) {
                    write!(w, " {}", v + 1)?;
                }
                writeln!(w)?;
            }
            offset += mesh.vertex_count();
        }
        for line in polylines.iter().filter(|l| l.len() >= 2) {
            for p in line {
                writeln!(w, "v {} {} {}", p[0], p[1], p[2])?;
            }
            write!(w, "l")?;
            for i in 0..line.len() {
                write!(w, " {}", offset + i)?;
            }
            writeln!(w)?;
            offset += line.len();
        }
        Ok(())
    })
}
