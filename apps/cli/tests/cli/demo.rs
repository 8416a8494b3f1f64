//! End-to-end test of `tvf demo` in its reduced-size mode (`--quick`): the page references
//! pictures that exist, reports every step with its time, and bad meshes are refused.

use crate::common::{assert_success, tvf};
use tvf_core::generate::genus_surface;
use tvf_core::io::write_obj;
use tvf_core::TriangleMesh;

/// The `src` attributes of every `<img>` in `page`.
fn image_sources(page: &str) -> Vec<String> {
    page.split("<img src=\"")
        .skip(1)
        .filter_map(|rest| rest.split('"').next())
        .map(str::to_string)
        .collect()
}

const STEPS: [&str; 7] = [
    "Mesh and Fourier basis",
    "Eigenfields (Figure 1)",
    "Hodge decomposition",
    "Filtering a noisy field (Figures 7 and 8)",
    "Compression: rate and distortion (Figure 9)",
    "Spline and soft design (Figure 4)",
    "Fur along the spline field (Figure 5)",
];

#[test]
fn quick_demo_writes_a_page_with_existing_pictures_and_step_times() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("demo-out");
    let output = tvf()
        .args(["demo", "--quick", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    let sources = image_sources(&page);
    assert!(sources.len() >= 9, "{sources:?}");
    for name in [
        "mesh.png",
        "figure1_eigenfields.png",
        "harmonic.png",
        "hodge.png",
        "figure7_filtering.png",
        "figure8_spectrum.png",
        "figure9_rate_distortion.png",
        "design.png",
        "fur.png",
    ] {
        assert!(sources.iter().any(|s| s == name), "{name} not on the page");
    }
    for source in &sources {
        let path = out.join(source);
        let image = image::open(&path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .to_rgba8();
        let drawn = image
            .pixels()
            .filter(|p| p.0 != [255, 255, 255, 255])
            .count();
        assert!(
            drawn as f64 > 0.05 * (image.width() * image.height()) as f64,
            "{source} is nearly empty"
        );
    }
    // Every step is in the page's time table and on stderr, with a time.
    for (k, step) in STEPS.iter().enumerate() {
        let escaped = step.replace('&', "&amp;");
        assert!(
            page.contains(&format!("<tr><td>{escaped}</td><td>")),
            "{step}"
        );
        assert!(
            stderr.contains(&format!("demo [{}/7] {step}: ", k + 1)),
            "{step} missing on stderr:\n{stderr}"
        );
    }
    assert!(page.contains("<th>total</th>"));
    // The numbers the sections promise: hard constraints met, soft ones not.
    assert!(page.contains("spline: worst relative constraint residual"));
    let spline_residual: f64 = page
        .split("spline: worst relative constraint residual</td><td>")
        .nth(1)
        .and_then(|rest| rest.split('<').next())
        .and_then(|x| x.parse().ok())
        .expect("spline residual on the page");
    assert!(spline_residual < 1e-8, "{spline_residual}");
    // No temporary files left behind.
    for entry in std::fs::read_dir(&out).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(
            name == "index.html" || name.ends_with(".png"),
            "unexpected file {name}"
        );
    }
}

#[test]
fn demo_refuses_meshes_it_cannot_use() {
    let dir = tempfile::tempdir().unwrap();
    // Two triangles: too few eigenfields for the three pairs the demo shows.
    let tiny = TriangleMesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [1, 3, 2]],
    )
    .unwrap();
    let path = dir.path().join("tiny.obj");
    write_obj(&path, &tiny).unwrap();
    let output = tvf()
        .args(["demo", "-o"])
        .arg(dir.path().join("out"))
        .arg("--mesh")
        .arg(&path)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("three pairs"), "{stderr}");

    let missing = dir.path().join("missing.obj");
    let output = tvf()
        .args(["demo", "-o"])
        .arg(dir.path().join("out"))
        .arg("--mesh")
        .arg(&missing)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&output.stderr).contains("missing.obj"));

    // A closed genus-2 mesh works, quietly.
    let path = dir.path().join("genus2.obj");
    write_obj(&path, &genus_surface(2, 4)).unwrap();
    let out = dir.path().join("g2");
    let output = tvf()
        .args(["demo", "--quick", "--quiet", "-k", "24", "-o"])
        .arg(&out)
        .arg("--mesh")
        .arg(&path)
        .output()
        .unwrap();
    assert_success(&output);
    assert!(
        output.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(page.contains("genus 2"));
    assert!(page.contains("harmonic.png"));
}
