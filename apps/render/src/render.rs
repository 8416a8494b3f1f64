//! The renderer: rasterise, shade (colour map, LIC, headlight), draw the 3D overlays,
//! downsample, then add the colour bar and the title.

use image::RgbaImage;
use rayon::prelude::*;
use tvf_core::geometry::{add, dot, norm, normalize, scale, sub};
use tvf_core::TriangleMesh;

use crate::arrows::{arrow_glyphs, draw_arrow, draw_glyphs};
use crate::camera::Camera;
use crate::colorbar::{colorbar_margin, draw_colorbar, draw_title};
use crate::error::{check_face_count, check_finite_scalars, check_finite_vectors, RenderError};
use crate::lic::{lic_texture, PixelFaces};
use crate::overlay3d::{disc, segment, Ink};
use crate::raster::{rasterize, Frame, NO_HIT};
use crate::scene::{FieldStyle, RenderOptions, Scene, Shading};
use crate::streamlines::{trace_streamlines, Streamline};
use crate::surface::{centroid, mean_edge_length, tangential, vertex_normals};
use crate::text::TextSize;

fn unit(c: [u8; 3]) -> [f32; 3] {
    c.map(|v| v as f32 / 255.0)
}

fn validate(
    mesh: &TriangleMesh,
    scene: &Scene,
    options: &RenderOptions,
) -> Result<(), RenderError> {
    let ok = |v: u32| (16..=16384).contains(&v);
    if !ok(options.width) || !ok(options.height) {
        return Err(RenderError::InvalidSize {
            width: options.width,
            height: options.height,
        });
    }
    if !(1..=4).contains(&options.supersample) {
        return Err(RenderError::InvalidOption {
            name: "supersample",
            value: options.supersample.to_string(),
            reason: "must be 1, 2, 3 or 4",
        });
    }
    let finite = [
        options.yaw_degrees,
        options.pitch_degrees,
        options.zoom,
        options.ambient,
    ];
    if finite.iter().any(|v| !v.is_finite()) || options.zoom <= 0.0 {
        return Err(RenderError::InvalidOption {
            name: "view / zoom / ambient",
            value: format!("{:?}", finite),
            reason: "angles must be finite and zoom positive",
        });
    }
    if let Some(s) = &scene.face_scalar {
        check_face_count("face scalar", mesh.face_count(), s.values.len())?;
        check_finite_scalars("face scalar", &s.values)?;
    }
    for layer in &scene.fields {
        check_face_count("field", mesh.face_count(), layer.vectors.len())?;
        check_finite_vectors("field", &layer.vectors)?;
    }
    Ok(())
}

/// Renders `mesh` with `scene` into an RGBA image of `options.width × options.height`.
///
/// The camera is fitted to the mesh's bounding sphere (turned by the options' yaw and pitch),
/// the surface is shaded with ambient light plus a headlight (Lambert, two-sided), and
/// everything is supersampled `options.supersample²` times. Errors on per-face arrays of
/// the wrong length, non-finite values and invalid options.
pub fn render(
    mesh: &TriangleMesh,
    scene: &Scene,
    options: &RenderOptions,
) -> Result<RgbaImage, RenderError> {
    validate(mesh, scene, options)?;
    let (w, h) = (options.width as usize, options.height as usize);
    let text = TextSize::for_height(h as f64 / 40.0);
    let right = scene
        .face_scalar
        .as_ref()
        .map_or(0, |s| colorbar_margin(&s.scale, &s.label, text)) as f64;
    let top = if scene.title.is_some() {
        text.height() as f64 + 12.0
    } else {
        0.0
    };
    let viewport = [0.0, top, (w as f64 - right).max(8.0), h as f64 - top];
    let camera = Camera::fit(
        mesh.positions(),
        options.yaw_degrees,
        options.pitch_degrees,
        viewport,
        options.zoom,
    );
    let ss = options.supersample as usize;
    let sample_camera = camera.scaled(ss as f64);
    let mut frame = rasterize(mesh, &sample_camera, w * ss, h * ss);
    let edge = mean_edge_length(mesh);

    let texture = lic_texture_product(mesh, scene, &frame, ss, &camera, edge);
    shade(
        mesh,
        scene,
        options,
        &camera,
        &mut frame,
        texture.as_deref(),
        w,
    );
    let overlays = Overlays3d {
        mesh,
        camera: &camera,
        sample_camera: &sample_camera,
        ss: ss as f64,
        edge,
    };
    overlays.draw_fields(&mut frame, scene)?;
    overlays.draw_polylines(&mut frame, scene);
    overlays.draw_markers(&mut frame, scene);

    let mut image = downsample(&frame, ss, options.background);
    if let Some(s) = &scene.face_scalar {
        draw_colorbar(&mut image, &s.scale, &s.label, text);
    }
    if let Some(title) = &scene.title {
        draw_title(&mut image, title, text);
    }
    Ok(image)
}

/// The line integral convolution textures of the scene's LIC layers (one value per output
/// pixel, each `1 − strength + strength · LIC`), multiplied; `None` without LIC layers.
fn lic_texture_product(
    mesh: &TriangleMesh,
    scene: &Scene,
    frame: &Frame,
    ss: usize,
    camera: &Camera,
    edge: f64,
) -> Option<Vec<f32>> {
    let mut texture: Option<Vec<f32>> = None;
    for layer in &scene.fields {
        if let FieldStyle::Lic(lic) = &layer.style {
            let pixels = PixelFaces::from_frame(frame, ss);
            let dirs = screen_directions(mesh, &layer.vectors, camera, edge);
            let jump = (0.05 * camera.scene_radius()) as f32;
            let tex = lic_texture(&pixels, &dirs, jump, lic);
            let strength = lic.strength.clamp(0.0, 1.0) as f32;
            let tex: Vec<f32> = tex
                .into_iter()
                .map(|v| 1.0 - strength + strength * v)
                .collect();
            texture = Some(match texture {
                None => tex,
                Some(old) => old.iter().zip(&tex).map(|(a, b)| a * b).collect(),
            });
        }
    }
    texture
}

/// What the 3D overlays (arrows, streamlines, polylines, markers) are drawn with: the mesh, the
/// camera of the output image and that of the supersampled frame (`ss` samples per pixel and
/// axis), and the mean edge length (depth offsets, streamline steps).
struct Overlays3d<'a> {
    mesh: &'a TriangleMesh,
    camera: &'a Camera,
    sample_camera: &'a Camera,
    ss: f64,
    edge: f64,
}

impl Overlays3d<'_> {
    /// The arrow and streamline layers of the scene's fields (LIC layers are shaded instead).
    fn draw_fields(&self, frame: &mut Frame, scene: &Scene) -> Result<(), RenderError> {
        let ss = self.ss;
        for layer in &scene.fields {
            match &layer.style {
                FieldStyle::Arrows(opts) => {
                    let glyphs = arrow_glyphs(self.mesh, &layer.vectors, opts);
                    draw_glyphs(
                        frame,
                        self.sample_camera,
                        &glyphs,
                        opts.width_px * ss,
                        unit(opts.color),
                    );
                }
                FieldStyle::Streamlines(opts) => {
                    let lines = trace_streamlines(self.mesh, &layer.vectors, opts)?;
                    draw_streamlines(
                        frame,
                        self.sample_camera,
                        self.mesh,
                        &lines,
                        opts.width_px * ss,
                        unit(opts.color),
                        self.edge,
                    );
                }
                FieldStyle::Lic(_) => {}
            }
        }
        Ok(())
    }

    /// The scene's polylines, their colour blended from `color` at the start to `tip_color`
    /// at the end.
    fn draw_polylines(&self, frame: &mut Frame, scene: &Scene) {
        for line in &scene.polylines {
            let n = line.points.len();
            for (i, seg) in line.points.windows(2).enumerate() {
                let s0 = i as f32 / (n - 1) as f32;
                let s1 = (i + 1) as f32 / (n - 1) as f32;
                let (c0, c1) = (unit(line.color), unit(line.tip_color));
                let mix = |s: f32| [0, 1, 2].map(|k| c0[k] * (1.0 - s) + c1[k] * s);
                let ink = Ink {
                    color: [mix(s0), mix(s1)],
                    alpha: [1.0; 2],
                    depth_offset: 0.5 * self.edge,
                };
                segment(
                    frame,
                    self.sample_camera,
                    seg[0],
                    seg[1],
                    line.width_px * self.ss,
                    &ink,
                );
            }
        }
    }

    /// The scene's markers: a disc each, and an arrow (dark outline, coloured fill) along the
    /// marker's direction where it has a non-zero one.
    fn draw_markers(&self, frame: &mut Frame, scene: &Scene) {
        let (ss, edge) = (self.ss, self.edge);
        let arrow_length = 0.16 * self.camera.scene_radius();
        for m in &scene.markers {
            let ink = Ink {
                color: [unit(m.color), [0.1, 0.1, 0.1]],
                alpha: [1.0; 2],
                depth_offset: edge,
            };
            if let Some(d) = m.direction.filter(|d| norm(*d) > 0.0) {
                let tip = add(m.position, scale(normalize(d), arrow_length));
                let side_axis = self.camera.to_eye(m.position);
                let dark = Ink {
                    color: [[0.1, 0.1, 0.1]; 2],
                    ..ink
                };
                let fill = Ink {
                    depth_offset: arrow_length,
                    ..ink
                };
                // A dark outline, then the arrow in its colour drawn over it.
                for (width, ink) in [(3.5 * ss, &dark), (2.0 * ss, &fill)] {
                    let camera = self.sample_camera;
                    draw_arrow(frame, camera, m.position, tip, side_axis, width, ink);
                }
            }
            disc(
                frame,
                self.sample_camera,
                m.position,
                m.radius_px * ss,
                1.5 * ss,
                &ink,
            );
        }
    }
}

/// Each face's unit field direction in output-image coordinates (zero where the field
/// vanishes or points at the viewer).
fn screen_directions(
    mesh: &TriangleMesh,
    vectors: &[[f64; 3]],
    camera: &Camera,
    edge: f64,
) -> Vec<[f32; 2]> {
    (0..mesh.face_count())
        .into_par_iter()
        .map(|t| {
            let v = tangential(vectors[t], mesh.face_normal(t));
            if norm(v) == 0.0 {
                return [0.0; 2];
            }
            let c = centroid(mesh, t);
            let a = camera.project(c);
            let b = camera.project(add(c, scale(normalize(v), 0.1 * edge)));
            let d = [b[0] - a[0], b[1] - a[1]];
            let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
            if l > 1e-9 && l.is_finite() {
                [(d[0] / l) as f32, (d[1] / l) as f32]
            } else {
                [0.0; 2]
            }
        })
        .collect()
}

fn shade(
    mesh: &TriangleMesh,
    scene: &Scene,
    options: &RenderOptions,
    camera: &Camera,
    frame: &mut Frame,
    texture: Option<&[f32]>,
    out_width: usize,
) {
    let ss = options.supersample as usize;
    let normals = match options.shading {
        Shading::Smooth => Some(vertex_normals(mesh)),
        Shading::Flat => None,
    };
    let face_colors: Vec<[f32; 3]> = match &scene.face_scalar {
        Some(s) => s.values.iter().map(|&v| unit(s.scale.color(v))).collect(),
        None => Vec::new(),
    };
    let surface = unit(options.surface_color);
    let background = unit([
        options.background[0],
        options.background[1],
        options.background[2],
    ]);
    let bg_alpha = options.background[3] as f32 / 255.0;
    let ambient = options.ambient.clamp(0.0, 1.0) as f32;
    let light = scale(camera.forward(), -1.0);
    let width = frame.width;
    let (face, bary) = (&frame.face, &frame.bary);
    frame
        .color
        .par_chunks_mut(width)
        .zip(frame.alpha.par_chunks_mut(width))
        .enumerate()
        .for_each(|(y, (colors, alphas))| {
            for x in 0..width {
                let i = y * width + x;
                let t = face[i];
                if t == NO_HIT {
                    colors[x] = background;
                    alphas[x] = bg_alpha;
                    continue;
                }
                let t = t as usize;
                let n = match &normals {
                    None => mesh.face_normal(t),
                    Some(vn) => {
                        let f = mesh.faces()[t];
                        let [b1, b2] = bary[i].map(|b| b as f64);
                        let b0 = 1.0 - b1 - b2;
                        let s = [0, 1, 2]
                            .map(|k| b0 * vn[f[0]][k] + b1 * vn[f[1]][k] + b2 * vn[f[2]][k]);
                        normalize(s)
                    }
                };
                let lambert = dot(n, light).abs() as f32;
                let intensity = ambient + (1.0 - ambient) * lambert;
                let base = if face_colors.is_empty() {
                    surface
                } else {
                    face_colors[t]
                };
                let tex = texture.map_or(1.0, |tx| tx[(y / ss) * out_width + x / ss]);
                colors[x] = base.map(|c| (c * intensity * tex).min(1.0));
                alphas[x] = 1.0;
            }
        });
}

fn draw_streamlines(
    frame: &mut Frame,
    camera: &Camera,
    mesh: &TriangleMesh,
    lines: &[Streamline],
    width: f64,
    color: [f32; 3],
    edge: f64,
) {
    for line in lines {
        let total = line.length().max(1e-300);
        let mut run = 0.0;
        for (i, &t) in line.faces.iter().enumerate() {
            let (a, b) = (line.points[i], line.points[i + 1]);
            let len = norm(sub(b, a));
            let s0 = (run / total) as f32;
            run += len;
            let s1 = (run / total) as f32;
            let mid = scale(add(a, b), 0.5);
            if dot(mesh.face_normal(t), camera.to_eye(mid)) <= 0.0 {
                continue;
            }
            let ink = Ink {
                color: [color; 2],
                alpha: [0.15 + 0.85 * s0, 0.15 + 0.85 * s1],
                depth_offset: 0.5 * edge,
            };
            segment(frame, camera, a, b, width, &ink);
        }
    }
}

fn downsample(frame: &Frame, ss: usize, background: [u8; 4]) -> RgbaImage {
    let w = frame.width / ss;
    let h = frame.height / ss;
    let mut image = RgbaImage::new(w as u32, h as u32);
    let n = (ss * ss) as f32;
    let buffer: &mut [u8] = &mut image;
    buffer
        .par_chunks_mut(4 * w)
        .enumerate()
        .for_each(|(y, row)| {
            for x in 0..w {
                let mut c = [0f32; 3];
                let mut a = 0f32;
                for sy in 0..ss {
                    for sx in 0..ss {
                        let i = frame.index(x * ss + sx, y * ss + sy);
                        let al = frame.alpha[i];
                        for (sum, &v) in c.iter_mut().zip(&frame.color[i]) {
                            *sum += v * al;
                        }
                        a += al;
                    }
                }
                let px = &mut row[4 * x..4 * x + 4];
                if a > 0.0 {
                    for k in 0..3 {
                        px[k] = ((c[k] / a).clamp(0.0, 1.0) * 255.0).round() as u8;
                    }
                } else {
                    px[..3].copy_from_slice(&background[..3]);
                }
                px[3] = ((a / n).clamp(0.0, 1.0) * 255.0).round() as u8;
            }
        });
    image
}
