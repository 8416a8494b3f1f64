//! Shared fixtures: synthetic fields on generated meshes, and an optional folder to keep
//! the pictures for inspection (`TVF_RENDER_OUT=/some/dir`).

use std::path::{Path, PathBuf};

use image::RgbaImage;
use tvf_core::geometry::cross;
use tvf_core::TriangleMesh;

/// Face centroids.
pub fn centroids(mesh: &TriangleMesh) -> Vec<[f64; 3]> {
    let p = mesh.positions();
    mesh.faces()
        .iter()
        .map(|f| [0, 1, 2].map(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0))
        .collect()
}

/// The rotation field `ω × c` at each face centroid `c`.
pub fn rotation_field(mesh: &TriangleMesh, omega: [f64; 3]) -> Vec<[f64; 3]> {
    centroids(mesh)
        .into_iter()
        .map(|c| cross(omega, c))
        .collect()
}

/// The coordinate field `∂/∂v` around the tube of a torus of revolution about z
/// (unit length), at face centroids.
pub fn torus_tube_field(mesh: &TriangleMesh, major: f64) -> Vec<[f64; 3]> {
    centroids(mesh)
        .into_iter()
        .map(|c| {
            let u = c[1].atan2(c[0]);
            let rho = (c[0] * c[0] + c[1] * c[1]).sqrt() - major;
            let v = c[2].atan2(rho);
            [-v.sin() * u.cos(), -v.sin() * u.sin(), v.cos()]
        })
        .collect()
}

/// Saves `image` under `name` in a temporary folder (and in `$TVF_RENDER_OUT` when set),
/// and returns the temporary path.
pub fn keep(image: &RgbaImage, dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    tvf_render::save_png(image, &path).expect("write png");
    if let Ok(out) = std::env::var("TVF_RENDER_OUT") {
        let out = PathBuf::from(out);
        std::fs::create_dir_all(&out).expect("create output folder");
        tvf_render::save_png(image, &out.join(name)).expect("write png copy");
    }
    path
}

/// Whether two colours differ by at most `tol` in each channel.
pub fn close(a: [u8; 3], b: [u8; 3], tol: u8) -> bool {
    (0..3).all(|k| a[k].abs_diff(b[k]) <= tol)
}

/// RGB of pixel `(x, y)`.
pub fn rgb(image: &RgbaImage, x: u32, y: u32) -> [u8; 3] {
    let p = image.get_pixel(x, y).0;
    [p[0], p[1], p[2]]
}
