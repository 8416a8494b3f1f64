//! A torus with smooth bumps on its tube, placed deterministically.

use super::torus::torus_of_revolution;
use crate::TriangleMesh;
use std::f64::consts::TAU;

/// Torus of revolution around the z axis whose tube radius is modulated by `bump_count`
/// Gaussian bumps: the tube point at angles `(u, v)` sits at distance
/// `minor · (1 + bump_height · b(u, v))` from the tube's centre circle, with `b ∈ [0, 1]` a sum of
/// bumps (clamped) centred on a golden-ratio sequence of `(u, v)` positions, so the shape is the
/// same on every run and every machine.
///
/// `around × tube` grid, `2·around·tube` faces, genus 1, outward normals. Returns `None` unless
/// `around, tube ≥ 3`, `minor > 0`, `bump_height ≥ 0` and `minor·(1 + bump_height) < major`.
pub fn bumpy_torus(
    major: f64,
    minor: f64,
    around: usize,
    tube: usize,
    bump_count: usize,
    bump_height: f64,
) -> Option<TriangleMesh> {
    let valid = around >= 3
        && tube >= 3
        && minor > 0.0
        && bump_height >= 0.0
        && minor * (1.0 + bump_height) < major
        && major.is_finite();
    if !valid {
        return None;
    }
    let golden = (5f64.sqrt() - 1.0) / 2.0;
    let centres: Vec<(f64, f64)> = (0..bump_count)
        .map(|k| {
            let k = k as f64 + 1.0;
            (
                TAU * (k * golden).fract(),
                TAU * (k * golden * golden).fract(),
            )
        })
        .collect();
    // Bump width in radians: a fraction of the spacing of the bump centres on the torus.
    let width = TAU / (2.0 * (bump_count.max(1) as f64).sqrt());
    let periodic = |d: f64| {
        let d = d.rem_euclid(TAU);
        d.min(TAU - d)
    };
    let bump = |u: f64, v: f64| -> f64 {
        centres
            .iter()
            .map(|&(cu, cv)| {
                let (du, dv) = (periodic(u - cu), periodic(v - cv));
                (-(du * du + dv * dv) / (2.0 * (width / 2.5).powi(2))).exp()
            })
            .sum::<f64>()
            .min(1.0)
    };
    torus_of_revolution(major, around, tube, |u, v| {
        minor * (1.0 + bump_height * bump(u, v))
    })
}
