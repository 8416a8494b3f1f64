//! Renders of generated meshes with synthetic fields: sizes, coverage, colour bar, arrows,
//! streamlines, LIC, markers and polylines, plus the error paths.

use crate::common;
use crate::common::{close, keep, rgb, rotation_field, torus_tube_field};
use tvf_core::generate::{icosphere, torus};
use tvf_core::geometry::norm;
use tvf_render::{
    grow_fur, render, ArrowOptions, ColorMap, FaceScalar, FieldLayer, FieldStyle, FurOptions,
    LicOptions, Marker, Polyline, RenderError, RenderOptions, Scene, Shading, StreamlineOptions,
};

fn options(width: u32, height: u32) -> RenderOptions {
    RenderOptions {
        width,
        height,
        ..Default::default()
    }
}

/// Pixels at least 40 levels darker in `after` than in `before`.
fn darkened(before: &image::RgbaImage, after: &image::RgbaImage) -> usize {
    before
        .pixels()
        .zip(after.pixels())
        .filter(|(a, b)| a.0[0] as i32 - b.0[0] as i32 >= 40)
        .count()
}

fn count(image: &image::RgbaImage, pred: impl Fn([u8; 3]) -> bool) -> usize {
    image
        .pixels()
        .filter(|p| pred([p.0[0], p.0[1], p.0[2]]))
        .count()
}

#[test]
fn shaded_sphere_covers_the_expected_area() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(4);
    for shading in [Shading::Flat, Shading::Smooth] {
        let opts = RenderOptions {
            shading,
            ..options(400, 300)
        };
        let image = render(&mesh, &Scene::default(), &opts).unwrap();
        assert_eq!(image.dimensions(), (400, 300));
        keep(&image, dir.path(), &format!("sphere_{shading:?}.png"));
        let background = count(&image, |c| c == [255, 255, 255]);
        let fraction = 1.0 - background as f64 / (400.0 * 300.0);
        // The unit sphere is fitted to 94 % of the viewport height: a disc of radius 141
        // pixels, π·141² / 120000 ≈ 0.52.
        assert!(
            (0.49..0.55).contains(&fraction),
            "foreground fraction {fraction}"
        );
        // Headlight: the centre is brighter than a point near the silhouette.
        let centre = rgb(&image, 200, 150)[0];
        let rim = rgb(&image, 200 + 135, 150)[0];
        assert!(centre > rim + 40, "centre {centre} rim {rim}");
    }
}

#[test]
fn colour_map_has_a_colour_bar_with_the_map_colours() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(3);
    let field = rotation_field(&mesh, [0.0, 0.0, 1.0]);
    let magnitude: Vec<f64> = field.iter().map(|v| norm(*v)).collect();
    let scene = Scene {
        face_scalar: Some(FaceScalar::new(magnitude, ColorMap::Viridis, "|u|")),
        title: Some("rotation field magnitude".into()),
        ..Default::default()
    };
    let image = render(&mesh, &scene, &options(640, 480)).unwrap();
    keep(&image, dir.path(), "sphere_magnitude.png");
    // Somewhere in the right margin, a column runs from viridis yellow (top) to purple (bottom).
    let top = ColorMap::Viridis.color(1.0);
    let bottom = ColorMap::Viridis.color(0.0);
    let found = (540..640).any(|x| {
        let column: Vec<[u8; 3]> = (0..480).map(|y| rgb(&image, x, y)).collect();
        let first_top = column.iter().position(|&c| close(c, top, 6));
        let last_bottom = column.iter().rposition(|&c| close(c, bottom, 6));
        matches!((first_top, last_bottom), (Some(a), Some(b)) if b > a + 200)
    });
    assert!(found, "no colour bar found");
    // Diverging map: red and blue both appear for a signed scalar.
    let signed: Vec<f64> = common::centroids(&mesh).iter().map(|c| c[1]).collect();
    let scene = Scene {
        face_scalar: Some(FaceScalar::new(signed, ColorMap::BlueWhiteRed, "y")),
        ..Default::default()
    };
    let image = render(&mesh, &scene, &options(640, 480)).unwrap();
    keep(&image, dir.path(), "sphere_signed.png");
    let reds = count(&image, |c| c[0] > c[2] + 60);
    let blues = count(&image, |c| c[2] > c[0] + 60);
    assert!(reds > 2000 && blues > 2000, "reds {reds} blues {blues}");
}

#[test]
fn arrows_are_drawn_on_the_visible_side() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(4);
    let field = rotation_field(&mesh, [0.0, 1.0, 0.0]);
    let plain = render(&mesh, &Scene::default(), &options(500, 400)).unwrap();
    let scene = Scene {
        fields: vec![FieldLayer {
            vectors: field.clone(),
            style: FieldStyle::Arrows(ArrowOptions {
                max_count: 600,
                ..Default::default()
            }),
        }],
        ..Default::default()
    };
    let image = render(&mesh, &scene, &options(500, 400)).unwrap();
    keep(&image, dir.path(), "sphere_arrows.png");
    let changed = darkened(&plain, &image);
    assert!(changed > 3000, "{changed} pixels darkened by arrows");
    // Arrows stay on the sphere: nothing changes outside its silhouette (radius 188 pixels,
    // 94 % of half the image height, as the camera is fitted).
    let outside = image
        .enumerate_pixels()
        .zip(plain.pixels())
        .filter(|((x, y, p), q)| {
            let (dx, dy) = (*x as f64 - 250.0, *y as f64 - 200.0);
            p.0 != q.0 && (dx * dx + dy * dy).sqrt() > 191.0
        })
        .count();
    assert_eq!(outside, 0);
    // The arrows are spread evenly over the surface and lie in their face planes.
    let glyphs = tvf_render::arrow_glyphs(&mesh, &field, &ArrowOptions::default());
    assert!(
        glyphs.len() > 300 && glyphs.len() <= 1500,
        "{} glyphs",
        glyphs.len()
    );
    for g in &glyphs {
        let d = tvf_core::geometry::sub(g.tip, g.tail);
        assert!(tvf_core::geometry::dot(d, g.normal).abs() < 1e-12 * norm(d).max(1.0));
    }
}

#[test]
fn streamlines_and_lic_pictures() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = torus(1.0, 0.4, 96, 40).unwrap();
    let field = torus_tube_field(&mesh, 1.0);
    let plain = render(&mesh, &Scene::default(), &options(640, 480)).unwrap();
    let scene = Scene {
        fields: vec![FieldLayer {
            vectors: field.clone(),
            style: FieldStyle::Streamlines(StreamlineOptions {
                count: 400,
                ..Default::default()
            }),
        }],
        ..Default::default()
    };
    let image = render(&mesh, &scene, &options(640, 480)).unwrap();
    keep(&image, dir.path(), "torus_streamlines.png");
    let changed = darkened(&plain, &image);
    assert!(changed > 3000, "{changed} pixels darkened by streamlines");

    let scene = Scene {
        fields: vec![FieldLayer {
            vectors: field,
            style: FieldStyle::Lic(LicOptions::default()),
        }],
        ..Default::default()
    };
    let image = render(&mesh, &scene, &options(640, 480)).unwrap();
    keep(&image, dir.path(), "torus_lic.png");
}

#[test]
fn lic_is_smooth_along_the_field_and_rough_across_it() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(5);
    // Looking along −z at a rotation about z: circles around the image centre.
    let field = rotation_field(&mesh, [0.0, 0.0, 1.0]);
    let opts = RenderOptions {
        yaw_degrees: 0.0,
        pitch_degrees: 0.0,
        ..options(400, 400)
    };
    let scene = Scene {
        fields: vec![FieldLayer {
            vectors: field,
            style: FieldStyle::Lic(LicOptions::default()),
        }],
        ..Default::default()
    };
    let image = render(&mesh, &scene, &opts).unwrap();
    keep(&image, dir.path(), "sphere_lic_front.png");
    // Right of the centre the circles run vertically in the image.
    let (mut along, mut across) = (0.0, 0.0);
    for y in 170..230 {
        for x in 225..265 {
            let v = |x: u32, y: u32| rgb(&image, x, y)[0] as f64;
            along += (v(x, y + 1) - v(x, y)).abs();
            across += (v(x + 1, y) - v(x, y)).abs();
        }
    }
    assert!(across > 2.5 * along, "across {across} along {along}");
}

#[test]
fn markers_and_polylines_are_drawn_with_depth_test() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(4);
    let field = rotation_field(&mesh, [0.0, 0.0, 1.0]);
    let fur = grow_fur(
        &mesh.clone().into(),
        &field,
        &FurOptions {
            strand_count: 3000,
            ..Default::default()
        },
    )
    .unwrap();
    let polylines = fur
        .into_iter()
        .map(|points| Polyline {
            points,
            color: [90, 50, 20],
            tip_color: [240, 200, 120],
            width_px: 1.2,
        })
        .collect();
    let opts = RenderOptions {
        yaw_degrees: 0.0,
        pitch_degrees: 0.0,
        ..options(500, 400)
    };
    let scene = Scene {
        polylines,
        markers: vec![
            // Front (visible) and back (hidden) of the sphere.
            Marker {
                position: [0.0, 0.0, 1.0],
                color: Marker::constraint_color("source"),
                radius_px: 7.0,
                direction: None,
            },
            Marker {
                position: [0.0, 0.0, -1.0],
                color: Marker::constraint_color("sink"),
                radius_px: 7.0,
                direction: None,
            },
            Marker {
                position: [0.6, 0.0, 0.8],
                color: Marker::constraint_color("vector"),
                radius_px: 5.0,
                direction: Some([0.0, 1.0, 0.0]),
            },
        ],
        ..Default::default()
    };
    let image = render(&mesh, &scene, &opts).unwrap();
    keep(&image, dir.path(), "sphere_fur_markers.png");
    let red = count(&image, |c| close(c, Marker::constraint_color("source"), 20));
    let blue = count(&image, |c| close(c, Marker::constraint_color("sink"), 20));
    let orange = count(&image, |c| close(c, Marker::constraint_color("vector"), 20));
    assert!(red > 80, "visible marker: {red} pixels");
    assert_eq!(blue, 0, "the marker behind the sphere must be hidden");
    assert!(orange > 40, "vector marker: {orange} pixels");
    let hair = count(&image, |c| c[0] > c[2] + 40 && c[1] > c[2] + 20);
    assert!(hair > 5000, "fur pixels {hair}");
}

#[test]
fn bad_inputs_are_refused() {
    let mesh = icosphere(1);
    let short = Scene {
        fields: vec![FieldLayer {
            vectors: vec![[1.0, 0.0, 0.0]; 3],
            style: FieldStyle::Arrows(Default::default()),
        }],
        ..Default::default()
    };
    assert!(matches!(
        render(&mesh, &short, &options(100, 100)),
        Err(RenderError::FaceCountMismatch {
            expected: 80,
            actual: 3,
            ..
        })
    ));
    let nan = Scene {
        face_scalar: Some(FaceScalar::new(vec![f64::NAN; 80], ColorMap::Viridis, "x")),
        ..Default::default()
    };
    assert!(matches!(
        render(&mesh, &nan, &options(100, 100)),
        Err(RenderError::NonFinite { index: 0, .. })
    ));
    assert!(matches!(
        render(&mesh, &Scene::default(), &options(0, 100)),
        Err(RenderError::InvalidSize { .. })
    ));
    let opts = RenderOptions {
        supersample: 9,
        ..options(100, 100)
    };
    let err = render(&mesh, &Scene::default(), &opts).unwrap_err();
    assert!(err.to_string().contains("supersample"), "{err}");
}
