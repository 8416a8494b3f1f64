//! A torus of revolution around the z axis.

use super::quad_grid::{grid_cell, split_quad, Diagonal};
use crate::TriangleMesh;
use std::f64::consts::TAU;

/// Torus with major radius `major` (centre to tube centre) and minor radius `minor` (tube),
/// `around` segments along the major circle and `tube` along the minor one
/// (`2·around·tube` faces, genus 1, outward normals).
///
/// Returns `None` unless `0 < minor < major` and both resolutions are at least 3.
pub fn torus(major: f64, minor: f64, around: usize, tube: usize) -> Option<TriangleMesh> {
    let valid = minor > 0.0 && minor < major && around >= 3 && tube >= 3;
    if !valid || !major.is_finite() {
        return None;
    }
    torus_of_revolution(major, around, tube, |_, _| minor)
}

/// The `around × tube` grid of a torus of revolution around the z axis whose tube radius at
/// angles `(u, v)` (around the z axis, around the tube; radians) is `tube_radius(u, v)`:
/// `2·around·tube` counter-clockwise faces, outward normals while `0 < tube_radius < major`.
pub(crate) fn torus_of_revolution(
    major: f64,
    around: usize,
    tube: usize,
    tube_radius: impl Fn(f64, f64) -> f64,
) -> Option<TriangleMesh> {
    let (positions, quads) = torus_grid(major, around, tube, tube_radius);
    let faces = quads
        .into_iter()
        .flat_map(|quad| split_quad(quad, Diagonal::AC))
        .collect();
    TriangleMesh::new(positions, faces).ok()
}

/// The vertices and the `around · tube` counter-clockwise quads of the grid of
/// [`torus_of_revolution`].
pub(crate) fn torus_grid(
    major: f64,
    around: usize,
    tube: usize,
    tube_radius: impl Fn(f64, f64) -> f64,
) -> (Vec<[f64; 3]>, Vec<[usize; 4]>) {
    let mut positions = Vec::with_capacity(around * tube);
    for i in 0..around {
        let u = TAU * i as f64 / around as f64;
        for j in 0..tube {
            let v = TAU * j as f64 / tube as f64;
            let r = tube_radius(u, v);
            let radius = major + r * v.cos();
            positions.push([radius * u.cos(), radius * u.sin(), r * v.sin()]);
        }
    }
    let index = |i: usize, j: usize| (i % around) * tube + (j % tube);
    let quads = (0..around)
        .flat_map(|i| (0..tube).map(move |j| grid_cell(index, i, j)))
        .collect();
    (positions, quads)
}
