//! A perspective camera fitted to a mesh's bounding box and turned by yaw and pitch.

use tvf_core::geometry::{add, cross, dot, normalize, scale, sub};

/// Vertical field of view in degrees.
const FIELD_OF_VIEW_DEGREES: f64 = 30.0;

/// A pinhole camera looking at the centre of a bounding sphere.
///
/// Image coordinates are pixels with the origin at the top-left corner, `x` to the right
/// and `y` down; the depth of a point is its distance along the viewing direction (in the
/// mesh's length units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    eye: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    forward: [f64; 3],
    focal: f64,
    center: [f64; 2],
    radius: f64,
}

impl Camera {
    /// Fits a camera to `points`: the eye looks at their bounding-box centre from a distance
    /// at which the enclosing sphere just fits the 30° field of view, and the image scale and
    /// offset are chosen so that the projected points fill 94 % of the viewport
    /// `[x0, x0 + width] × [y0, y0 + height]` (pixels), centred; `zoom` magnifies about the
    /// viewport centre.
    ///
    /// With `yaw = pitch = 0` the camera looks along `−z` with `+y` up. `yaw_degrees` turns
    /// the camera about the vertical axis (positive: the camera moves towards `+x`), and
    /// `pitch_degrees` raises it (positive: looking down on the object); pitch is clamped to
    /// `±89°`.
    pub fn fit(
        points: &[[f64; 3]],
        yaw_degrees: f64,
        pitch_degrees: f64,
        viewport: [f64; 4],
        zoom: f64,
    ) -> Camera {
        let [x0, y0, width, height] = viewport;
        let (lo, hi) = bounding_box(points);
        let center_world = scale(add(lo, hi), 0.5);
        let radius = points
            .iter()
            .map(|&p| tvf_core::geometry::norm(sub(p, center_world)))
            .fold(0.0, f64::max)
            .max(1e-12);
        let yaw = yaw_degrees.to_radians();
        let pitch = pitch_degrees.clamp(-89.0, 89.0).to_radians();
        let to_eye = [
            yaw.sin() * pitch.cos(),
            pitch.sin(),
            yaw.cos() * pitch.cos(),
        ];
        let forward = scale(to_eye, -1.0);
        let right = normalize(cross(forward, [0.0, 1.0, 0.0]));
        let up = cross(right, forward);
        let half_fov = 0.5 * FIELD_OF_VIEW_DEGREES.to_radians();
        let eye = add(center_world, scale(to_eye, radius / half_fov.sin()));
        // Extents of the points on the image plane at unit distance.
        let (mut umin, mut umax, mut vmin, mut vmax) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for &p in points {
            let d = sub(p, eye);
            let z = dot(d, forward).max(1e-12 * radius);
            let (u, v) = (dot(d, right) / z, dot(d, up) / z);
            umin = umin.min(u);
            umax = umax.max(u);
            vmin = vmin.min(v);
            vmax = vmax.max(v);
        }
        let zoom = if zoom.is_finite() && zoom > 0.0 {
            zoom
        } else {
            1.0
        };
        let fit_u = width / (umax - umin).max(1e-12);
        let fit_v = height / (vmax - vmin).max(1e-12);
        let focal = 0.94 * fit_u.min(fit_v) * zoom;
        Camera {
            eye,
            right,
            up,
            forward,
            focal,
            center: [
                x0 + 0.5 * width - focal * 0.5 * (umin + umax),
                y0 + 0.5 * height + focal * 0.5 * (vmin + vmax),
            ],
            radius,
        }
    }

    /// The same camera for an image `factor` times larger in each direction (used for
    /// supersampling).
    pub fn scaled(&self, factor: f64) -> Camera {
        Camera {
            focal: self.focal * factor,
            center: [self.center[0] * factor, self.center[1] * factor],
            ..*self
        }
    }

    /// Projects `p` to `[x, y, depth]`; depth ≤ [`Camera::near`] means behind the camera.
    #[inline]
    pub fn project(&self, p: [f64; 3]) -> [f64; 3] {
        let d = sub(p, self.eye);
        let z = dot(d, self.forward);
        let zs = if z.abs() < 1e-300 { 1e-300 } else { z };
        [
            self.center[0] + self.focal * dot(d, self.right) / zs,
            self.center[1] - self.focal * dot(d, self.up) / zs,
            z,
        ]
    }

    /// Smallest depth drawn.
    pub fn near(&self) -> f64 {
        1e-3 * self.radius
    }

    /// Unit viewing direction (from the eye into the scene).
    pub fn forward(&self) -> [f64; 3] {
        self.forward
    }

    /// Unit direction from `p` towards the eye.
    pub fn to_eye(&self, p: [f64; 3]) -> [f64; 3] {
        normalize(sub(self.eye, p))
    }

    /// Radius of the bounding sphere the camera was fitted to.
    pub fn scene_radius(&self) -> f64 {
        self.radius
    }
}

/// The axis-aligned bounding box `(lo, hi)` of `points` (`([0;3], [0;3])` when empty).
pub fn bounding_box(points: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    if points.is_empty() {
        return ([0.0; 3], [0.0; 3]);
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fitted_sphere_stays_inside_viewport() {
        let corners: Vec<[f64; 3]> = (0..8)
            .map(|i| [0, 1, 2].map(|k| if i >> k & 1 == 1 { 1.0 } else { -1.0 }))
            .collect();
        let cam = Camera::fit(&corners, 30.0, 20.0, [0.0, 0.0, 400.0, 300.0], 1.0);
        for &p in &corners {
            let q = cam.project(p);
            assert!(q[2] > cam.near());
            assert!(
                (0.0..=400.0).contains(&q[0]) && (0.0..=300.0).contains(&q[1]),
                "{q:?}"
            );
        }
        // Symmetric about the viewing axis: the centre projects to the viewport centre.
        let front = Camera::fit(&corners, 0.0, 0.0, [0.0, 0.0, 400.0, 300.0], 1.0);
        let c = front.project([0.0; 3]);
        assert!((c[0] - 200.0).abs() < 1e-9 && (c[1] - 150.0).abs() < 1e-9);
        // The projected points fill 94 % of the height (the limiting extent).
        let ys: Vec<f64> = corners.iter().map(|&p| front.project(p)[1]).collect();
        let span = ys.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
            - ys.iter().cloned().fold(f64::INFINITY, f64::min);
        assert!((span - 0.94 * 300.0).abs() < 1e-6, "{span}");
    }
}
