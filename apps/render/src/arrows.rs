//! Arrow glyphs for a per-face field, and the arrow of a vector marker.

use tvf_core::geometry::{add, cross, dot, norm, normalize, scale, sub};
use tvf_core::TriangleMesh;

use crate::camera::Camera;
use crate::overlay3d::{segment, triangle, Ink};
use crate::raster::Frame;
use crate::scene::ArrowOptions;
use crate::spacing::spread;
use crate::surface::{centroid, mean_edge_length, tangential};

/// One arrow in 3D: shaft from `tail` to `neck`, head triangle `neck ± half_width` to `tip`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArrowGlyph {
    /// Start of the shaft.
    pub tail: [f64; 3],
    /// Tip of the head.
    pub tip: [f64; 3],
    /// Face the arrow stands on.
    pub face: usize,
    /// Unit normal of that face.
    pub normal: [f64; 3],
}

/// The arrows drawn for `vectors` (one per face): at evenly spread faces, centred at the
/// face centroid, in the face plane, the longest `length_scale × spacing` long. Arrows of
/// vanishing vectors are left out.
pub fn arrow_glyphs(
    mesh: &TriangleMesh,
    vectors: &[[f64; 3]],
    options: &ArrowOptions,
) -> Vec<ArrowGlyph> {
    let spacing =
        mean_edge_length(mesh).max((mesh.total_area() / options.max_count.max(1) as f64).sqrt());
    let centroids: Vec<[f64; 3]> = (0..mesh.face_count()).map(|t| centroid(mesh, t)).collect();
    let tangent: Vec<[f64; 3]> = vectors
        .iter()
        .enumerate()
        .map(|(t, &v)| tangential(v, mesh.face_normal(t)))
        .collect();
    let largest = tangent.iter().map(|&v| norm(v)).fold(0.0, f64::max);
    if largest <= 0.0 {
        return Vec::new();
    }
    spread(&centroids, spacing, options.seed)
        .into_iter()
        .filter_map(|t| {
            let v = tangent[t];
            let length = options.length_scale * spacing * norm(v) / largest;
            if length < 1e-3 * spacing {
                return None;
            }
            let d = normalize(v);
            let c = centroids[t];
            Some(ArrowGlyph {
                tail: sub(c, scale(d, 0.5 * length)),
                tip: add(c, scale(d, 0.5 * length)),
                face: t,
                normal: mesh.face_normal(t),
            })
        })
        .collect()
}

/// Draws an arrow from `tail` to `tip` whose head lies in the plane orthogonal to `side_axis`
/// (the face normal for glyphs on the surface).
pub(crate) fn draw_arrow(
    frame: &mut Frame,
    camera: &Camera,
    tail: [f64; 3],
    tip: [f64; 3],
    side_axis: [f64; 3],
    width: f64,
    ink: &Ink,
) {
    let along = sub(tip, tail);
    let length = norm(along);
    if length <= 0.0 {
        return;
    }
    let d = scale(along, 1.0 / length);
    let head = 0.35 * length;
    let side = normalize(cross(side_axis, d));
    let neck = sub(tip, scale(d, head));
    segment(
        frame,
        camera,
        tail,
        add(neck, scale(d, 0.3 * head)),
        width,
        ink,
    );
    let half = scale(side, 0.45 * head);
    triangle(frame, camera, [tip, add(neck, half), sub(neck, half)], ink);
}

/// Draws the glyphs, skipping those on faces turned away from the viewer.
pub(crate) fn draw_glyphs(
    frame: &mut Frame,
    camera: &Camera,
    glyphs: &[ArrowGlyph],
    width: f64,
    color: [f32; 3],
) {
    for g in glyphs {
        let mid = scale(add(g.tail, g.tip), 0.5);
        if dot(g.normal, camera.to_eye(mid)) <= 0.0 {
            continue;
        }
        let ink = Ink {
            color: [color; 2],
            alpha: [1.0; 2],
            depth_offset: 0.5 * norm(sub(g.tip, g.tail)),
        };
        draw_arrow(frame, camera, g.tail, g.tip, g.normal, width, &ink);
    }
}
