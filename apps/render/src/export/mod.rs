//! Exports for other tools: VTK legacy (ParaView), PLY (MeshLab, Polyscope), OBJ with
//! polylines; and PNG images. Every file is written atomically. A tangent field's data for
//! them: `field_export`.

mod atomic;
mod field_export;
mod obj;
mod ply;
mod vtk;

pub use atomic::write_atomically;
pub use field_export::streamline_polylines;
pub use obj::write_obj;
pub use ply::write_ply;
pub use vtk::write_vtk;

use std::io::Write;
use std::path::Path;

use image::RgbaImage;
use tvf_core::SurfaceMesh;

use crate::error::{check_face_count, check_finite_scalars, check_finite_vectors, RenderError};

/// Named per-face data written along with a mesh.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FaceData {
    /// Vector fields: name and one 3D vector per face.
    pub vectors: Vec<(String, Vec<[f64; 3]>)>,
    /// Scalar fields: name and one value per face.
    pub scalars: Vec<(String, Vec<f64>)>,
}

fn check_name(name: &str, format: &'static str) -> Result<(), RenderError> {
    if name.is_empty() || name.chars().any(|c| c.is_whitespace() || c.is_control()) {
        return Err(RenderError::InvalidName {
            name: name.to_string(),
            format,
            reason: "names must be non-empty and contain no whitespace",
        });
    }
    Ok(())
}

fn check_data(
    mesh: &SurfaceMesh,
    data: &FaceData,
    format: &'static str,
) -> Result<(), RenderError> {
    for (name, values) in &data.vectors {
        check_name(name, format)?;
        check_face_count(name, mesh.face_count(), values.len())?;
        check_finite_vectors(name, values)?;
    }
    for (name, values) in &data.scalars {
        check_name(name, format)?;
        check_face_count(name, mesh.face_count(), values.len())?;
        check_finite_scalars(name, values)?;
    }
    Ok(())
}

/// Writes `image` to `path` as PNG, atomically.
pub fn save_png(image: &RgbaImage, path: &Path) -> Result<(), RenderError> {
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .map_err(|e| RenderError::Png {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    write_atomically(path, |w| w.write_all(&bytes))
}
