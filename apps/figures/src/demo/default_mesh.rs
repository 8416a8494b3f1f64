//! The demo's own mesh, used when none is given: a bumpy torus standing upright
//! ([`default_mesh`]), with 14,400 faces (a small one for `tvf demo --quick`).

use crate::error::FigureError;
use tvf_core::generate::bumpy_torus;
use tvf_core::{SurfaceMesh, TriangleMesh};

/// Vertices of the default bumpy torus around its axis (`2 · around · tube` faces).
const TORUS_AROUND: usize = 120;

/// Vertices of the default bumpy torus around its tube.
const TORUS_TUBE: usize = 60;

/// The bumpy torus of the demo (`quick`: the small one for tests) turned so that its axis
/// points up in pictures, and its name for the page.
pub fn default_mesh(quick: bool) -> Result<(SurfaceMesh, String), FigureError> {
    let (mesh, name) = if quick {
        (
            bumpy_torus(1.0, 0.3, 40, 20, 12, 0.35),
            "bumpy torus (quick)",
        )
    } else {
        let mesh = bumpy_torus(1.0, 0.3, TORUS_AROUND, TORUS_TUBE, 24, 0.35);
        (mesh, "bumpy torus")
    };
    let invalid = || FigureError::Invalid("the built-in bumpy torus parameters are invalid".into());
    let mesh = upright(&mesh.ok_or_else(invalid)?).ok_or_else(invalid)?;
    Ok((mesh, name.to_string()))
}

/// The mesh turned so that its z axis points up in pictures (+y): `(x, y, z) ↦ (x, z, −y)`, a
/// rotation, so orientation and intrinsic geometry are unchanged.
fn upright(mesh: &TriangleMesh) -> Option<SurfaceMesh> {
    let positions = mesh
        .positions()
        .iter()
        .map(|p| [p[0], p[2], -p[1]])
        .collect();
    TriangleMesh::new(positions, mesh.faces().to_vec())
        .ok()
        .map(SurfaceMesh::from)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quick_torus_stands_upright_with_its_area_kept() {
        let (mesh, name) = default_mesh(true).unwrap();
        assert_eq!(name, "bumpy torus (quick)");
        assert_eq!((mesh.face_count(), mesh.genus()), (2 * 40 * 20, 1));
        let lying = bumpy_torus(1.0, 0.3, 40, 20, 12, 0.35).unwrap();
        assert!((mesh.total_area() - lying.total_area()).abs() < 1e-12 * lying.total_area());
        // The axis (z of the lying torus) is now y: the torus is thin along y.
        let extent = |axis: usize| {
            let values = mesh.positions().iter().map(|p| p[axis]);
            values.clone().fold(f64::MIN, f64::max) - values.fold(f64::MAX, f64::min)
        };
        assert!(extent(1) < 0.5 * extent(0) && extent(1) < 0.5 * extent(2));
    }
}
