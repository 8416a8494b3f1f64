//! End-to-end tests of `tvf render` and `tvf export`: the real binary on a generated torus
//! (written as OBJ) with a rotation field, checking the files it writes.

use crate::common::tvf;
use std::path::{Path, PathBuf};
use std::process::Output;
use tvf_core::generate::torus;
use tvf_core::io::{load_mesh, write_obj};
use tvf_core::TriangleMesh;

fn run(args: &[&std::ffi::OsStr]) -> Output {
    tvf().args(args).output().unwrap()
}

fn ok(output: &Output) {
    assert!(
        output.status.success(),
        "exit {:?}\nstdout: {}\nstderr: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}

struct Fixture {
    dir: tempfile::TempDir,
    mesh_path: PathBuf,
    field_path: PathBuf,
    mesh: TriangleMesh,
}

impl Fixture {
    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }
}

/// A torus about z and the rotation field about z (tangent to it), as a text file.
fn fixture() -> Fixture {
    let dir = tempfile::tempdir().unwrap();
    let mesh_path = dir.path().join("torus.obj");
    write_obj(&mesh_path, &torus(1.0, 0.4, 32, 16).unwrap()).unwrap();
    let mesh = load_mesh(&mesh_path)
        .unwrap()
        .mesh
        .into_triangles()
        .unwrap();
    let p = mesh.positions();
    let text: String = mesh
        .faces()
        .iter()
        .map(|f| {
            let c: [f64; 3] = std::array::from_fn(|k| (p[f[0]][k] + p[f[1]][k] + p[f[2]][k]) / 3.0);
            format!("{} {} {}\n", -c[1], c[0], 0.0)
        })
        .collect();
    let field_path = dir.path().join("rotation.txt");
    std::fs::write(&field_path, text).unwrap();
    Fixture {
        dir,
        mesh_path,
        field_path,
        mesh,
    }
}

fn os(s: &str) -> &std::ffi::OsStr {
    std::ffi::OsStr::new(s)
}

fn load_png(path: &Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

/// Fraction of pixels that are not the white background.
fn ink(image: &image::RgbaImage) -> f64 {
    let drawn = image
        .pixels()
        .filter(|p| p.0 != [255, 255, 255, 255])
        .count();
    drawn as f64 / (image.width() * image.height()) as f64
}

/// Pixels close to `color`.
fn count_near(image: &image::RgbaImage, color: [u8; 3]) -> usize {
    image
        .pixels()
        .filter(|p| (0..3).all(|k| (p.0[k] as i32 - color[k] as i32).abs() <= 12))
        .count()
}

#[test]
fn render_writes_pictures_of_the_requested_size_in_every_style() {
    let fx = fixture();
    let mut images = Vec::new();
    for (style, color) in [
        ("arrows", "magnitude"),
        ("streamlines", "curl"),
        ("lic", "divergence"),
        ("none", "energy"),
    ] {
        let out = fx.path(&format!("{style}.png"));
        let output = run(&[
            os("render"),
            fx.mesh_path.as_os_str(),
            fx.field_path.as_os_str(),
            os("-o"),
            out.as_os_str(),
            os("--size"),
            os("320x240"),
            os("--style"),
            os(style),
            os("--color"),
            os(color),
            os("--view"),
            os("20,-30"),
        ]);
        ok(&output);
        let image = load_png(&out);
        assert_eq!(image.dimensions(), (320, 240), "{style}");
        let covered = ink(&image);
        assert!(covered > 0.2 && covered < 0.95, "{style}: {covered}");
        images.push(image);
    }
    for i in 0..images.len() {
        for j in i + 1..images.len() {
            assert_ne!(images[i], images[j], "styles {i} and {j} look the same");
        }
    }
    // The mesh alone, from a built-in example.
    let out = fx.path("mesh.png");
    ok(&run(&[
        os("render"),
        os("--example"),
        os("icosphere"),
        os("-o"),
        out.as_os_str(),
        os("--size"),
        os("200x100"),
    ]));
    let image = load_png(&out);
    assert_eq!(image.dimensions(), (200, 100));
    assert!(ink(&image) > 0.1);
}

#[test]
fn render_overlays_constraints_and_draws_hodge_parts() {
    let fx = fixture();
    let constraints = fx.path("c.json");
    std::fs::write(
        &constraints,
        r#"{"constraints": [
            {"id": "v", "kind": "vector", "face": 0, "value": [1, 0, 0]},
            {"id": "s", "kind": "divergence", "vertex": 100, "value": 2.0},
            {"id": "w", "kind": "curl", "edge": 40, "value": -1.0}]}"#,
    )
    .unwrap();
    let plain = fx.path("plain.png");
    let marked = fx.path("marked.png");
    for (out, extra) in [(&plain, None), (&marked, Some(&constraints))] {
        let mut args = vec![
            os("render"),
            fx.mesh_path.as_os_str(),
            fx.field_path.as_os_str(),
            os("-o"),
            out.as_os_str(),
            os("--size"),
            os("400x300"),
            os("--color"),
            os("none"),
            os("--view"),
            os("0,60"),
        ];
        if let Some(c) = extra {
            args.extend([os("--constraints"), c.as_os_str()]);
        }
        ok(&run(&args));
    }
    let (plain, marked) = (load_png(&plain), load_png(&marked));
    // Source markers are red (220, 30, 30), vortices green (20, 170, 60): only with --constraints.
    for color in [[220, 30, 30], [20, 170, 60]] {
        assert_eq!(count_near(&plain, color), 0, "{color:?}");
        assert!(count_near(&marked, color) > 5, "{color:?}");
    }

    let parts = fx.path("parts.png");
    let output = run(&[
        os("render"),
        fx.mesh_path.as_os_str(),
        fx.field_path.as_os_str(),
        os("-o"),
        parts.as_os_str(),
        os("--parts"),
        os("--size"),
        os("400x300"),
    ]);
    ok(&output);
    let image = load_png(&parts);
    assert_eq!(image.dimensions(), (400, 300));
    // Four panels, each with a surface.
    for (x0, y0) in [(0, 0), (200, 0), (0, 150), (200, 150)] {
        let drawn = (x0..x0 + 200)
            .flat_map(|x| (y0..y0 + 150).map(move |y| (x, y)))
            .filter(|&(x, y)| image.get_pixel(x, y).0 != [255, 255, 255, 255])
            .count();
        assert!(
            drawn > 3000,
            "panel at ({x0}, {y0}) has {drawn} drawn pixels"
        );
    }
}

#[test]
fn render_refuses_bad_input_with_a_clear_message() {
    let fx = fixture();
    let short = fx.path("short.txt");
    std::fs::write(&short, "1 0 0\n0 1 0\n").unwrap();
    let output = run(&[
        os("render"),
        fx.mesh_path.as_os_str(),
        short.as_os_str(),
        os("-o"),
        fx.path("x.png").as_os_str(),
    ]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("short.txt"), "{stderr}");
    let output = run(&[
        os("render"),
        fx.mesh_path.as_os_str(),
        os("-o"),
        fx.path("x.png").as_os_str(),
        os("--size"),
        os("9x9"),
    ]);
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("9x9"));
    let bad = fx.path("bad.json");
    std::fs::write(
        &bad,
        r#"{"constraints": [{"id": "v", "kind": "vector", "face": 99999, "value": [1, 0, 0]}]}"#,
    )
    .unwrap();
    let output = run(&[
        os("render"),
        fx.mesh_path.as_os_str(),
        os("-o"),
        fx.path("x.png").as_os_str(),
        os("--constraints"),
        bad.as_os_str(),
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("bad.json"));
    assert!(!fx.path("x.png").exists());
}

fn lines_starting(text: &str, prefix: &str) -> usize {
    text.lines().filter(|l| l.starts_with(prefix)).count()
}

#[test]
fn export_writes_vtk_ply_and_obj_with_the_right_counts() {
    let fx = fixture();
    let (v, f) = (fx.mesh.vertex_count(), fx.mesh.face_count());

    let vtk = fx.path("field.vtk");
    ok(&run(&[
        os("export"),
        fx.mesh_path.as_os_str(),
        fx.field_path.as_os_str(),
        os("--format"),
        os("vtk"),
        os("-o"),
        vtk.as_os_str(),
    ]));
    let text = std::fs::read_to_string(&vtk).unwrap();
    assert!(text.contains(&format!("POINTS {v} double")));
    assert!(text.contains(&format!("POLYGONS {f} {}", 4 * f)));
    assert!(text.contains(&format!("CELL_DATA {f}")));
    assert!(text.contains("VECTORS field double"));
    for name in ["magnitude", "divergence", "curl", "energy"] {
        assert!(text.contains(&format!("SCALARS {name} double 1")), "{name}");
    }
    assert_eq!(lines_starting(&text, "3 "), f);

    // PLY, format from the extension; the magnitude of the rotation field is the distance
    // from the axis, which is at least 1 − 0.4.
    let ply = fx.path("field.ply");
    ok(&run(&[
        os("export"),
        fx.mesh_path.as_os_str(),
        fx.field_path.as_os_str(),
        os("-o"),
        ply.as_os_str(),
    ]));
    let text = std::fs::read_to_string(&ply).unwrap();
    assert!(text.contains(&format!("element vertex {v}")));
    assert!(text.contains(&format!("element face {f}")));
    assert!(text.contains("property double field_x"));
    assert!(text.contains("property double magnitude"));
    let body: Vec<&str> = text.split("end_header\n").nth(1).unwrap().lines().collect();
    assert_eq!(body.len(), v + f);
    for face_line in &body[v..] {
        let values: Vec<f64> = face_line
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        // 3 v0 v1 v2, field x y z, magnitude, divergence, curl, energy.
        assert_eq!(values.len(), 4 + 3 + 4);
        assert!(
            values[7] > 0.5 && values[7] < 1.5,
            "magnitude {}",
            values[7]
        );
    }

    let obj = fx.path("lines.obj");
    ok(&run(&[
        os("export"),
        fx.mesh_path.as_os_str(),
        fx.field_path.as_os_str(),
        os("--format"),
        os("obj"),
        os("-o"),
        obj.as_os_str(),
    ]));
    let text = std::fs::read_to_string(&obj).unwrap();
    assert_eq!(lines_starting(&text, "f "), f);
    let polylines: Vec<&str> = text.lines().filter(|l| l.starts_with("l ")).collect();
    assert!(polylines.len() >= 5, "{} streamlines", polylines.len());
    let polyline_points: usize = polylines
        .iter()
        .map(|l| l.split_whitespace().count() - 1)
        .sum();
    assert_eq!(lines_starting(&text, "v "), v + polyline_points);
    // Streamlines of a rotation about z stay at constant height z (circles about the axis).
    let vertices: Vec<[f64; 3]> = text
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| {
            let c: Vec<f64> = l[2..]
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            [c[0], c[1], c[2]]
        })
        .collect();
    let first: Vec<usize> = polylines[0][2..]
        .split_whitespace()
        .map(|i| i.parse::<usize>().unwrap() - 1)
        .collect();
    let z: Vec<f64> = first.iter().map(|&i| vertices[i][2]).collect();
    let spread = z.iter().fold(f64::NEG_INFINITY, |m, &x| m.max(x))
        - z.iter().fold(f64::INFINITY, |m, &x| m.min(x));
    assert!(spread < 0.05, "streamline height varies by {spread}");

    let output = run(&[
        os("export"),
        fx.mesh_path.as_os_str(),
        fx.field_path.as_os_str(),
        os("-o"),
        fx.path("field.xyz").as_os_str(),
    ]);
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("field.xyz"));
}
