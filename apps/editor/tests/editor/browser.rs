//! End to end in a real headless browser (Debian's chromium driven by chromedriver over the
//! WebDriver protocol): load the editor for an icosphere, add a vector constraint by dragging on
//! the canvas, check that the server's field satisfies it and that the page shows the update;
//! then trigger a conflicting constraint (the page must show the error) and fur mode. On a mesh
//! with boundary (a pair of pants), with both boundary conditions: place a vector constraint and
//! a source by mouse and check that the page shows the server's finite field. On a cube-sphere of
//! quads (polygon-dec): the page draws the polygons' sides, a drag adds a vector constraint at a
//! point of the quad under the cursor (four corner weights, the point the ray hits on the drawn
//! surface), a click a source; the server's field satisfies both.
//!
//! Skips with a message when chromium or chromedriver are not installed (`.ci/browser-setup`
//! installs them). Screenshots go to `$TVF_SCREENSHOT_DIR` (default: the target's temp dir).

#[path = "common/webdriver.rs"]
mod webdriver;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crate::common::{icosphere_server_for, pants_server_for, polygon_server, Client};
use tvf_core::discretization::BoundaryCondition;
use tvf_discretizations::DEFAULT_DISCRETIZATION;
use webdriver::{find_executable, Browser};

fn screenshot_dir() -> PathBuf {
    std::env::var_os("TVF_SCREENSHOT_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("editor-screenshots"))
}

fn save(name: &str, png: &[u8]) {
    let dir = screenshot_dir();
    std::fs::create_dir_all(&dir).expect("screenshot directory");
    let path = dir.join(name);
    std::fs::write(&path, png).expect("write screenshot");
    println!("screenshot: {}", path.display());
}

#[test]
fn editor_page_adds_a_constraint_in_a_headless_browser() {
    drive_the_editor(DEFAULT_DISCRETIZATION, "editor");
}

/// The same session on a non-default catalog entry: DEC 1-forms, whose fields the server samples
/// into face frames for the page.
#[test]
fn editor_page_works_with_dec_one_forms() {
    drive_the_editor("dec-circumcentric", "editor-dec");
}

/// The browser pair `(chromium, chromedriver)`, or `None` with a message outside CI (in CI a
/// missing browser fails the test).
fn browser_executables(what: &str) -> Option<(PathBuf, PathBuf)> {
    let (Some(chromium), Some(chromedriver)) =
        (find_executable("chromium"), find_executable("chromedriver"))
    else {
        // In CI (.ci/browser-setup installs them) a missing browser is a failure, not a skip.
        assert!(
            std::env::var("CI").map_or(true, |v| v != "true"),
            "CI=true but chromium or chromedriver is not on PATH (run .ci/browser-setup)"
        );
        println!("SKIPPED the browser test on {what}: chromium or chromedriver not on PATH (run .ci/browser-setup)");
        return None;
    };
    Some((chromium, chromedriver))
}

/// Waits (up to 10 s) until the page shows the field version the server holds; returns the
/// server's check.
fn wait_until_the_page_shows_the_server_field(
    browser: &Browser,
    client: &Client,
) -> serde_json::Value {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let check = client.check();
        let version = check["version"].as_u64().unwrap();
        let shown: u64 = browser
            .script("return document.body.dataset.version;")
            .unwrap()
            .as_str()
            .and_then(|v| v.parse().ok())
            .unwrap_or(0);
        if shown == version || Instant::now() > deadline {
            return check;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// On a pair of pants (three boundary loops) with both boundary conditions, for the default
/// entry and DEC (relative forms for `normal`): the page starts,
/// a drag in an interior face adds a vector constraint and a click with the source tool a
/// divergence constraint in another interior face; the server's field satisfies both, the page
/// shows its version and residual, and every vector the page draws is finite (and not all zero).
#[test]
fn editor_page_edits_a_pair_of_pants_with_both_boundary_conditions() {
    let Some((chromium, chromedriver)) = browser_executables("a pair of pants") else {
        return;
    };
    for (id, boundary) in [DEFAULT_DISCRETIZATION, "dec-circumcentric"]
        .into_iter()
        .flat_map(|id| BoundaryCondition::ALL.map(|b| (id, b)))
    {
        let prefix = format!("editor-pants-{id}-{}", boundary.name());
        let (server, mesh) = pants_server_for(id, boundary);
        let mesh = mesh.as_triangles().expect("the pants are triangles");
        let client = Client::new(&server);
        let browser =
            Browser::start(&chromedriver, &chromium, 1200, 800).expect("headless chromium session");
        browser.goto(&server.url()).expect("open the page");
        let ready = browser
            .wait_for("return document.body.dataset.ready || (document.body.dataset.error ? 'error: ' + document.body.dataset.error : null);", Duration::from_secs(20))
            .expect("page starts");
        assert_eq!(
            ready, "true",
            "{id} {boundary:?}: the page failed to start: {ready}"
        );
        let before = browser.screenshot().expect("screenshot");
        save(&format!("{prefix}-1-loaded.png"), &before);
        // Two interior faces (no boundary vertex), the ones farthest apart along x.
        let mut on_boundary = vec![false; mesh.vertex_count()];
        for e in mesh.boundary_edges() {
            for v in mesh.edges()[e] {
                on_boundary[v] = true;
            }
        }
        let interior: Vec<usize> = (0..mesh.face_count())
            .filter(|&t| mesh.faces()[t].iter().all(|&v| !on_boundary[v]))
            .collect();
        let x = |t: usize| mesh.corner(t, 0)[0];
        let left = *interior
            .iter()
            .min_by(|&&a, &&b| x(a).total_cmp(&x(b)))
            .unwrap();
        let right = *interior
            .iter()
            .max_by(|&&a, &&b| x(a).total_cmp(&x(b)))
            .unwrap();
        let screen = |face: usize| {
            let p = browser
                .script(&format!(
                    "const {{ app, screenOf }} = window.tvfEditor;                      const s = screenOf(app.mesh.pointAt({face}, [1/3, 1/3, 1/3]));                      const r = document.getElementById('view').getBoundingClientRect();                      return [Math.round(r.left + s[0]), Math.round(r.top + s[1])];"
                ))
                .expect("screen position of a face");
            (p[0].as_i64().unwrap(), p[1].as_i64().unwrap())
        };
        let (lx, ly) = screen(left);
        browser
            .drag((lx, ly), (lx + 60, ly - 25))
            .expect("drag on the canvas");
        browser
            .wait_for("return document.getElementById('constraint-count').textContent === '1' && !document.querySelector('#error:not([hidden])');", Duration::from_secs(10))
            .expect("the page shows one constraint");
        browser
            .click(&browser.element("button[data-tool=source]").unwrap())
            .unwrap();
        let (rx, ry) = screen(right);
        browser
            .drag((rx, ry), (rx, ry))
            .expect("click for a source");
        browser
            .wait_for(
                "return document.getElementById('constraint-count').textContent === '2' && !document.querySelector('#error:not([hidden])');",
                Duration::from_secs(10),
            )
            .expect("the source is added");
        let check = wait_until_the_page_shows_the_server_field(&browser, &client);
        let constraints = check["constraints"].as_array().expect("constraints");
        assert_eq!(constraints.len(), 2, "{id} {boundary:?}: {check}");
        assert!(
            check["max_relative"].as_f64().unwrap() < 1e-9,
            "{id} {boundary:?}: the held field misses the constraints: {check}"
        );
        let shown = browser
            .script(
                "const v = window.tvfEditor.app.vectors;                  let finite = true, largest = 0;                  for (const x of v) { finite = finite && Number.isFinite(x); largest = Math.max(largest, Math.abs(x)); }                  return [document.body.dataset.version, document.getElementById('residual').textContent, finite, largest, v.length];",
            )
            .unwrap();
        assert_eq!(
            shown[0].as_str().unwrap(),
            check["version"].as_u64().unwrap().to_string(),
            "{id} {boundary:?}: the page shows the server's field version"
        );
        let residual: f64 = shown[1].as_str().unwrap().parse().expect("residual shown");
        assert!(residual < 1e-9, "{id} {boundary:?}: residual {residual}");
        assert_eq!(
            shown[2], true,
            "{id} {boundary:?}: the page holds a non-finite vector"
        );
        assert!(
            shown[3].as_f64().unwrap() > 0.0,
            "{id} {boundary:?}: the field is zero"
        );
        assert_eq!(shown[4].as_u64().unwrap() as usize, 3 * mesh.face_count());
        let after = browser.screenshot().expect("screenshot");
        save(&format!("{prefix}-2-constraints.png"), &after);
        assert_ne!(before, after, "{id} {boundary:?}: the picture changed");
        drop(browser);
        server.shutdown();
    }
}

/// Loads the page for the catalog entry `id`, adds a vector constraint by dragging, checks the
/// field and the page, provokes a conflict, adds a source and grows fur; screenshots are named
/// `{prefix}-*.png`.
fn drive_the_editor(id: &str, prefix: &str) {
    let Some((chromium, chromedriver)) = browser_executables(id) else {
        return;
    };
    let started = Instant::now();
    let server = icosphere_server_for(id);
    let client = Client::new(&server);
    let browser =
        Browser::start(&chromedriver, &chromium, 1200, 800).expect("headless chromium session");
    browser.goto(&server.url()).expect("open the page");
    let ready = browser
        .wait_for("return document.body.dataset.ready || (document.body.dataset.error ? 'error: ' + document.body.dataset.error : null);", Duration::from_secs(20))
        .expect("page starts");
    assert_eq!(ready, "true", "the page failed to start: {ready}");
    // WebGL2 really renders: the canvas centre is the shaded sphere, not the background.
    let before = browser.screenshot().expect("screenshot");
    save(&format!("{prefix}-1-loaded.png"), &before);
    assert_eq!(
        browser
            .script("return document.getElementById('constraint-count').textContent;")
            .unwrap(),
        "0"
    );

    // Drag from the centre of the canvas to the right and up: a vector constraint.
    let centre = browser
        .script("const r = document.getElementById('view').getBoundingClientRect(); return [Math.round(r.left + r.width / 2), Math.round(r.top + r.height / 2)];")
        .expect("canvas position");
    let (cx, cy) = (centre[0].as_i64().unwrap(), centre[1].as_i64().unwrap());
    browser
        .drag((cx, cy), (cx + 90, cy - 30))
        .expect("drag on the canvas");
    browser
        .wait_for("return document.getElementById('constraint-count').textContent === '1' && !document.querySelector('#error:not([hidden])');", Duration::from_secs(10))
        .expect("the page shows one constraint");
    // Wait until the server answered the last drag step and the page has shown it.
    let check = wait_until_the_page_shows_the_server_field(&browser, &client);
    let constraints = check["constraints"].as_array().expect("constraints");
    assert_eq!(constraints.len(), 1, "{check}");
    assert!(
        check["max_relative"].as_f64().unwrap() < 1e-9,
        "the held field misses the constraint: {check}"
    );
    let (_, saved) = client.get("/api/constraints");
    let saved: serde_json::Value = serde_json::from_slice(&saved).unwrap();
    let record = &saved["constraints"][0];
    assert_eq!(record["kind"], "vector", "{saved}");
    let value: Vec<f64> = record["value"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(
        value.iter().map(|x| x * x).sum::<f64>().sqrt() > 0.1,
        "the drag set a length: {value:?}"
    );
    let shown = browser.script("return [document.body.dataset.version, document.getElementById('residual').textContent];").unwrap();
    assert_eq!(
        shown[0].as_str().unwrap(),
        check["version"].as_u64().unwrap().to_string(),
        "page shows the server's field version"
    );
    let residual: f64 = shown[1]
        .as_str()
        .unwrap()
        .parse()
        .expect("residual shown as a number");
    assert!(residual < 1e-9, "{residual}");
    let after = browser.screenshot().expect("screenshot");
    save(&format!("{prefix}-2-vector-constraint.png"), &after);
    assert_ne!(before, after, "the picture changed");

    // A second vector constraint in the same face with another direction conflicts: the page
    // must show the server's refusal.
    // Zoom in, then start the drag in the same face as the first constraint but away from its
    // marker (a press on the marker would select and move it).
    let start = browser
        .script(
            "const { app, screenOf } = window.tvfEditor; app.camera.zoom(0.4); \
             const c = app.status.constraints[0], a = app.status.anchors[0]; \
             const anchor = screenOf(app.mesh.pointAt(a.face, a.barycentric)); \
             let best = null; \
             for (const b of [[0.8, 0.1, 0.1], [0.1, 0.8, 0.1], [0.1, 0.1, 0.8]]) { \
               const s = screenOf(app.mesh.pointAt(c.face, b)); \
               const d = Math.hypot(s[0] - anchor[0], s[1] - anchor[1]); \
               if (!best || d > best.d) best = { d, s }; } \
             const r = document.getElementById('view').getBoundingClientRect(); \
             return [Math.round(r.left + best.s[0]), Math.round(r.top + best.s[1]), best.d];",
        )
        .expect("a point in the constrained face");
    assert!(start[2].as_f64().unwrap() > 14.0, "{start}");
    let (sx, sy) = (start[0].as_i64().unwrap(), start[1].as_i64().unwrap());
    browser
        .drag((sx, sy), (sx - 40, sy + 70))
        .expect("second drag");
    let error = browser
        .wait_for(
            "const e = document.getElementById('error'); return e.hidden ? null : e.textContent;",
            Duration::from_secs(10),
        )
        .expect("the error area shows the conflict");
    assert!(error.as_str().unwrap().contains("conflicting"), "{error}");
    save(
        &format!("{prefix}-3-conflict-error.png"),
        &browser.screenshot().unwrap(),
    );
    assert_eq!(client.check()["constraints"].as_array().unwrap().len(), 1);

    // Add a source elsewhere, then fur mode.
    browser
        .click(&browser.element("button[data-tool=source]").unwrap())
        .unwrap();
    browser
        .drag((cx - 110, cy + 60), (cx - 110, cy + 60))
        .expect("click for a source");
    browser
        .wait_for(
            "return document.getElementById('constraint-count').textContent === '2';",
            Duration::from_secs(10),
        )
        .expect("the source is added");
    browser.click(&browser.element("#fur").unwrap()).unwrap();
    browser
        .wait_for("return window.__furStrands > 0;", Duration::from_secs(15))
        .expect("fur is drawn");
    assert!(client.check()["max_relative"].as_f64().unwrap() < 1e-9);
    save(
        &format!("{prefix}-4-fur.png"),
        &browser.screenshot().unwrap(),
    );
    drop(browser);
    server.shutdown();
    println!(
        "browser test on {id} took {:.1} s",
        started.elapsed().as_secs_f64()
    );
}

/// On a cube-sphere of non-planar quads with polygon-dec: the page starts with the quads as faces
/// (150 quads drawn as 600 fan triangles; odd, so that the view's centre is inside a quad) and their sides drawn; a pick at the canvas centre is a
/// point of a quad with four corner weights at the point the ray hits on the drawn surface; a drag
/// there adds a vector constraint and a click with the source tool a divergence constraint; the
/// server's field satisfies both and the page shows it, one finite vector per quad.
#[test]
fn editor_page_edits_the_quads_of_a_cube_sphere() {
    let Some((chromium, chromedriver)) = browser_executables("a quad mesh") else {
        return;
    };
    let mesh = tvf_core::SurfaceMesh::from(tvf_core::generate::cube_sphere(5).expect("quads"));
    let server = polygon_server(&mesh);
    let client = Client::new(&server);
    let browser =
        Browser::start(&chromedriver, &chromium, 1200, 800).expect("headless chromium session");
    browser.goto(&server.url()).expect("open the page");
    let ready = browser
        .wait_for("return document.body.dataset.ready || (document.body.dataset.error ? 'error: ' + document.body.dataset.error : null);", Duration::from_secs(20))
        .expect("page starts");
    assert_eq!(ready, "true", "the page failed to start: {ready}");
    let before = browser.screenshot().expect("screenshot");
    save("editor-quads-1-loaded.png", &before);
    let layout = browser
        .script(
            "const { app } = window.tvfEditor; const m = app.mesh; \
             const outlines = app.renderer.layers.get('outlines'); \
             return [m.isTriangleMesh, m.faceCount, m.triangleCount, outlines ? outlines.count : 0, \
                     document.getElementById('outlines-row').hidden, app.vectors.length];",
        )
        .unwrap();
    assert_eq!(
        layout,
        serde_json::json!([false, 150, 600, 2 * 4 * 150, false, 3 * 150])
    );
    // The pick at the canvas centre: a quad, four weights, at the ray's hit on the surface.
    let pick = browser
        .script(
            "const { app } = window.tvfEditor; const c = document.getElementById('view'); \
             const { origin, dir } = app.camera.ray(c.clientWidth / 2, c.clientHeight / 2, c.clientWidth, c.clientHeight); \
             const hit = app.mesh.pick(origin, dir); \
             const onRay = origin.map((x, k) => x + hit.distance * dir[k]); \
             const gap = Math.hypot(...onRay.map((x, k) => x - hit.point[k])); \
             return [hit.face, hit.barycentric, gap / app.mesh.radius];",
        )
        .unwrap();
    let weights: Vec<f64> = pick[1]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_f64().unwrap())
        .collect();
    assert_eq!(weights.len(), 4, "{pick}");
    assert!(weights.iter().all(|&w| w >= 0.0), "{pick}");
    assert!((weights.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{pick}");
    assert!(pick[2].as_f64().unwrap() < 1e-5, "{pick}");
    let centre = browser
        .script("const r = document.getElementById('view').getBoundingClientRect(); return [Math.round(r.left + r.width / 2), Math.round(r.top + r.height / 2)];")
        .expect("canvas position");
    let (cx, cy) = (centre[0].as_i64().unwrap(), centre[1].as_i64().unwrap());
    browser
        .drag((cx, cy), (cx + 90, cy - 30))
        .expect("drag on the canvas");
    browser
        .wait_for("return document.getElementById('constraint-count').textContent === '1' && !document.querySelector('#error:not([hidden])');", Duration::from_secs(10))
        .expect("the page shows one constraint");
    browser
        .click(&browser.element("button[data-tool=source]").unwrap())
        .unwrap();
    browser
        .drag((cx - 110, cy + 60), (cx - 110, cy + 60))
        .expect("click for a source");
    browser
        .wait_for(
            "return document.getElementById('constraint-count').textContent === '2' && !document.querySelector('#error:not([hidden])');",
            Duration::from_secs(10),
        )
        .expect("the source is added");
    let check = wait_until_the_page_shows_the_server_field(&browser, &client);
    assert_eq!(check["constraints"].as_array().unwrap().len(), 2, "{check}");
    assert!(
        check["max_relative"].as_f64().unwrap() < 1e-9,
        "the held field misses the constraints: {check}"
    );
    let (_, saved) = client.get("/api/constraints");
    let saved: serde_json::Value = serde_json::from_slice(&saved).unwrap();
    for record in saved["constraints"].as_array().unwrap() {
        let face = record["face"].as_u64().unwrap() as usize;
        assert!(face < 150, "{saved}");
        assert_eq!(
            record["barycentric"].as_array().unwrap().len(),
            4,
            "{saved}"
        );
    }
    assert_eq!(saved["constraints"][0]["face"], pick[0], "{saved}");
    let shown = browser
        .script(
            "const v = window.tvfEditor.app.vectors; let finite = true, largest = 0; \
             for (const x of v) { finite = finite && Number.isFinite(x); largest = Math.max(largest, Math.abs(x)); } \
             return [document.body.dataset.version, finite, largest];",
        )
        .unwrap();
    assert_eq!(
        shown[0].as_str().unwrap(),
        check["version"].as_u64().unwrap().to_string()
    );
    assert_eq!(shown[1], true);
    assert!(shown[2].as_f64().unwrap() > 0.0);
    let after = browser.screenshot().expect("screenshot");
    save("editor-quads-2-constraints.png", &after);
    assert_ne!(before, after, "the picture changed");
    drop(browser);
    server.shutdown();
}
