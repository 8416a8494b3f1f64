//! End-to-end tests of `tvf filter`, `analyze`, `compress`, `decompress` and `rate-distortion`:
//! the real binary on a generated torus (written as OBJ) with a basis file made by the library.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use tvf_core::discretization::FieldSampling;
use tvf_core::generate::torus;
use tvf_core::io::{load_mesh, write_obj};
use tvf_core::TriangleMesh;
use tvf_discretizations::{Conforming, FaceFields, MassLumping, Nonconforming};
use tvf_spectral::{
    compute_basis, read_face_vectors, save_basis, write_face_vector_sequence, BasisFileKey,
    BasisRequest, NpyDtype,
};

struct Fixture {
    dir: tempfile::TempDir,
    mesh: PathBuf,
    basis: PathBuf,
    field: PathBuf,
    loaded: TriangleMesh,
}

impl Fixture {
    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }
}

/// A smooth-ish field with a normal component (which the tools drop): a swirl about z, a wave,
/// and a small normal part.
fn swirl(mesh: &TriangleMesh, phase: f64) -> Vec<[f64; 3]> {
    let p = mesh.positions();
    mesh.faces()
        .iter()
        .enumerate()
        .map(|(t, f)| {
            let c: [f64; 3] = std::array::from_fn(|i| (p[f[0]][i] + p[f[1]][i] + p[f[2]][i]) / 3.0);
            let n = mesh.face_normal(t);
            let wave = (3.0 * c[0] + phase).sin();
            std::array::from_fn(|i| [-c[1], c[0], 0.0][i] + wave * [0.0, 0.0, 1.0][i] + 0.1 * n[i])
        })
        .collect()
}

fn write_text_field(path: &Path, vectors: &[[f64; 3]]) {
    let text: String = vectors
        .iter()
        .map(|v| format!("{} {} {}\n", v[0], v[1], v[2]))
        .collect();
    std::fs::write(path, text).unwrap();
}

fn fixture() -> Fixture {
    let dir = tempfile::tempdir().unwrap();
    let mesh_path = dir.path().join("torus.obj");
    write_obj(&mesh_path, &torus(1.0, 0.45, 24, 12).unwrap()).unwrap();
    // The basis belongs to the mesh exactly as the tool will read it.
    let loaded = load_mesh(&mesh_path)
        .unwrap()
        .mesh
        .into_triangles()
        .unwrap();
    let complex = Conforming::new(&loaded, MassLumping::Barycentric).unwrap();
    // The complete basis (dense eigensolvers, 2F = 576 fields): compression keeps only the
    // pairs asked for, and the tools see the same file format as for a truncated basis.
    let basis = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    let basis_path = dir.path().join("torus.tvfb");
    save_basis(&basis_path, &basis, &BasisFileKey::new(&loaded, &complex)).unwrap();
    let field = dir.path().join("field.txt");
    write_text_field(&field, &swirl(&loaded, 0.0));
    Fixture {
        dir,
        mesh: mesh_path,
        basis: basis_path,
        field,
        loaded,
    }
}

fn tvf(args: &[&dyn AsRef<std::ffi::OsStr>]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_tvf"));
    for a in args {
        command.arg(a);
    }
    command.output().unwrap()
}

fn succeeded(output: &Output) -> String {
    let stdout = String::from_utf8_lossy(&output.stdout).to_string();
    assert!(
        output.status.success(),
        "tvf failed: {}\n{stdout}",
        String::from_utf8_lossy(&output.stderr)
    );
    stdout
}

fn failed(output: &Output) -> String {
    assert!(!output.status.success(), "tvf should have failed");
    String::from_utf8_lossy(&output.stderr).to_string()
}

/// Tangent field (`2F`) of a vector file.
fn tangent(fields: &FaceFields, path: &Path) -> Vec<f64> {
    fields
        .from_face_vectors(&read_face_vectors(path).unwrap())
        .unwrap()
        .field
}

fn norm(fields: &FaceFields, v: &[f64]) -> f64 {
    v.iter()
        .zip(fields.mass())
        .map(|(x, m)| x * x * m)
        .sum::<f64>()
        .sqrt()
}

fn relative_error(fields: &FaceFields, a: &[f64], b: &[f64]) -> f64 {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    norm(fields, &d) / norm(fields, a)
}

#[test]
fn filter_identity_returns_the_tangent_field_and_low_pass_smooths() {
    let fx = fixture();
    let fields = FaceFields::new(&fx.loaded).unwrap();
    let out = fx.path("identity.npy");
    succeeded(&tvf(&[
        &"filter", &fx.mesh, &fx.field, &"--basis", &fx.basis, &"-o", &out,
    ]));
    let input = tangent(&fields, &fx.field);
    assert!(relative_error(&fields, &input, &tangent(&fields, &out)) < 1e-12);

    let smooth = fx.path("smooth.txt");
    let stdout = succeeded(&tvf(&[
        &"filter",
        &fx.mesh,
        &fx.field,
        &"--basis",
        &fx.basis,
        &"--integrable",
        &"lowpass:t=0.05",
        &"--cointegrable",
        &"curve:0,1;4,0.5;8,0",
        &"--rest",
        &"0",
        &"-o",
        &smooth,
    ]));
    assert!(stdout.contains("rest norm"), "{stdout}");
    let filtered = tangent(&fields, &smooth);
    assert!(norm(&fields, &filtered) < norm(&fields, &input));

    // Without --rest the rest gets the low-pass's gain at the basis's top frequency: the
    // unrepresented high frequencies are removed (the README's example once kept them as noise).
    let default_rest = fx.path("default-rest.txt");
    let stdout = succeeded(&tvf(&[
        &"filter",
        &fx.mesh,
        &fx.field,
        &"--basis",
        &fx.basis,
        &"--integrable",
        &"lowpass:t=5",
        &"--cointegrable",
        &"lowpass:t=5",
        &"-o",
        &default_rest,
    ]));
    // The fixture's basis represents its field whole (no rest to see removed): the default
    // gain itself is checked, e^(-5 λ_max) against the 1 that kept the rest before.
    let gain: f64 = stdout
        .lines()
        .find_map(|l| l.strip_prefix("rest gain"))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|g| g.parse().ok())
        .unwrap_or_else(|| panic!("no rest gain: {stdout}"));
    assert!(
        stdout.contains("(the filters' gain at the basis's highest frequency)") && gain < 1e-3,
        "{stdout}"
    );

    let error = failed(&tvf(&[
        &"filter",
        &fx.mesh,
        &fx.field,
        &"--basis",
        &fx.basis,
        &"--integrable",
        &"lowpass:s=1",
        &"-o",
        &smooth,
    ]));
    assert!(error.contains("lowpass:t="), "{error}");
}

#[test]
fn analyze_writes_the_spectrum_and_the_energy_split() {
    let fx = fixture();
    let dir = fx.path("analysis");
    succeeded(&tvf(&[
        &"analyze", &fx.mesh, &fx.field, &"--basis", &fx.basis, &"-o", &dir,
    ]));
    let csv = std::fs::read_to_string(dir.join("coefficients.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 2 * fx.loaded.face_count());
    assert!(rows.iter().filter(|r| r.contains(",harmonic,")).count() == 2);
    let png = std::fs::read(dir.join("spectrum.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("energy.json")).unwrap()).unwrap();
    let total = report["field_energy"].as_f64().unwrap();
    let basis_total = report["basis"]["total"].as_f64().unwrap();
    assert!((basis_total - total).abs() < 1e-9 * total);
    let hodge = &report["hodge"];
    let hodge_total = hodge["integrable"].as_f64().unwrap()
        + hodge["cointegrable"].as_f64().unwrap()
        + hodge["harmonic"].as_f64().unwrap();
    assert!((hodge_total - total).abs() < 1e-8 * total);
    // The basis represents part of each family; the harmonic part completely.
    assert!(
        report["basis"]["integrable"].as_f64().unwrap()
            <= hodge["integrable"].as_f64().unwrap() * (1.0 + 1e-9)
    );
    assert!(
        (report["basis"]["harmonic"].as_f64().unwrap() - hodge["harmonic"].as_f64().unwrap()).abs()
            < 1e-8 * total
    );
}

fn compress_json(args: &[&dyn AsRef<std::ffi::OsStr>]) -> serde_json::Value {
    let mut all: Vec<&dyn AsRef<std::ffi::OsStr>> = vec![&"compress"];
    all.extend_from_slice(args);
    all.push(&"--json");
    serde_json::from_str(&succeeded(&tvf(&all))).unwrap()
}

#[test]
fn compress_and_decompress_a_field() {
    let fx = fixture();
    let fields = FaceFields::new(&fx.loaded).unwrap();
    let input = tangent(&fields, &fx.field);
    let exact = fx.path("exact.tvfc");
    let exact_report = compress_json(&[
        &fx.mesh, &fx.field, &"--basis", &fx.basis, &"--pairs", &"80", &"-o", &exact,
    ]);
    let quantised = fx.path("quantised.tvfc");
    let quantised_report = compress_json(&[
        &fx.mesh, &fx.field, &"--basis", &fx.basis, &"--pairs", &"80", &"--bits", &"12", &"-o",
        &quantised,
    ]);
    let exact_bytes = exact_report["bytes"].as_u64().unwrap();
    assert_eq!(exact_bytes, std::fs::metadata(&exact).unwrap().len());
    assert!(quantised_report["bytes"].as_u64().unwrap() * 3 < exact_bytes);
    let faces = fx.loaded.face_count() as f64;
    let rate = exact_report["rate_against_two_doubles"].as_f64().unwrap();
    assert!((rate - 16.0 * faces / exact_bytes as f64).abs() < 1e-9);

    for (file, report) in [(&exact, &exact_report), (&quantised, &quantised_report)] {
        let out = fx.path("decoded.npy");
        succeeded(&tvf(&[
            &"decompress",
            &fx.mesh,
            file,
            &"--basis",
            &fx.basis,
            &"-o",
            &out,
        ]));
        let error = relative_error(&fields, &input, &tangent(&fields, &out));
        let reported = report["mean_relative_error"].as_f64().unwrap();
        assert!(
            (error - reported).abs() < 1e-9,
            "{error} vs reported {reported}"
        );
        assert!(error < 0.2, "relative error {error}");
    }
}

#[test]
fn compress_a_sequence_from_a_folder_and_from_an_array() {
    let fx = fixture();
    let fields = FaceFields::new(&fx.loaded).unwrap();
    let frames: Vec<Vec<[f64; 3]>> = (0..4).map(|k| swirl(&fx.loaded, 0.4 * k as f64)).collect();
    let folder = fx.path("frames");
    std::fs::create_dir(&folder).unwrap();
    for (k, frame) in frames.iter().enumerate() {
        write_text_field(&folder.join(format!("f{k:02}.txt")), frame);
    }
    let array = fx.path("frames.npy");
    write_face_vector_sequence(&array, &frames, NpyDtype::F32).unwrap();
    for (source, out) in [
        (&folder, fx.path("decoded_frames")),
        (&array, fx.path("decoded.npy")),
    ] {
        let file = fx.path("sequence.tvfc");
        let report = compress_json(&[
            &fx.mesh, source, &"--basis", &fx.basis, &"--pairs", &"60", &"--bits", &"10", &"-o",
            &file,
        ]);
        assert_eq!(report["frames"], 4);
        assert_eq!(report["sequence"], true);
        let worst = report["worst_relative_error"].as_f64().unwrap();
        assert!(worst >= report["mean_relative_error"].as_f64().unwrap());
        succeeded(&tvf(&[
            &"decompress",
            &fx.mesh,
            &file,
            &"--basis",
            &fx.basis,
            &"-o",
            &out,
        ]));
        let decoded: Vec<Vec<[f64; 3]>> = if out.is_dir() {
            (0..4)
                .map(|k| read_face_vectors(&out.join(format!("frame_{k:05}.npy"))).unwrap())
                .collect()
        } else {
            tvf_spectral::read_face_vector_sequence(&out).unwrap()
        };
        assert_eq!(decoded.len(), 4);
        for (k, (original, back)) in frames.iter().zip(&decoded).enumerate() {
            let a = fields.from_face_vectors(original).unwrap().field;
            let b = fields.from_face_vectors(back).unwrap().field;
            let error = relative_error(&fields, &a, &b);
            let reported = report["relative_errors"][k].as_f64().unwrap();
            // The f32 array input is read as f32 values: compare with the reported error loosely.
            assert!(
                (error - reported).abs() < 1e-5,
                "frame {k}: {error} vs {reported}"
            );
            assert!(error <= worst + 1e-5);
        }
    }
}

#[test]
fn decompress_refuses_another_basis_and_damaged_files() {
    let fx = fixture();
    let file = fx.path("field.tvfc");
    compress_json(&[
        &fx.mesh, &fx.field, &"--basis", &fx.basis, &"--pairs", &"40", &"-o", &file,
    ]);
    let out = fx.path("out.npy");

    let complex = Nonconforming::new(&fx.loaded, MassLumping::Barycentric).unwrap();
    let other = compute_basis(&complex, &BasisRequest::complete()).unwrap();
    let other_path = fx.path("other.tvfb");
    save_basis(
        &other_path,
        &other,
        &BasisFileKey::new(&fx.loaded, &complex),
    )
    .unwrap();
    let error = failed(&tvf(&[
        &"decompress",
        &fx.mesh,
        &file,
        &"--basis",
        &other_path,
        &"-o",
        &out,
    ]));
    assert!(
        error.contains("another basis") && error.contains("field.tvfc"),
        "{error}"
    );

    let other_mesh = fx.path("other.obj");
    write_obj(&other_mesh, &torus(1.0, 0.3, 24, 12).unwrap()).unwrap();
    let error = failed(&tvf(&[
        &"decompress",
        &other_mesh,
        &file,
        &"--basis",
        &fx.basis,
        &"-o",
        &out,
    ]));
    assert!(error.contains("another mesh"), "{error}");

    let mut bytes = std::fs::read(&file).unwrap();
    let middle = bytes.len() / 2;
    bytes[middle] ^= 0x10;
    let damaged = fx.path("damaged.tvfc");
    std::fs::write(&damaged, &bytes).unwrap();
    let error = failed(&tvf(&[
        &"decompress",
        &fx.mesh,
        &damaged,
        &"--basis",
        &fx.basis,
        &"-o",
        &out,
    ]));
    assert!(
        error.contains("damaged") && error.contains("damaged.tvfc"),
        "{error}"
    );
    std::fs::write(&damaged, &bytes[..middle]).unwrap();
    let error = failed(&tvf(&[
        &"decompress",
        &fx.mesh,
        &damaged,
        &"--basis",
        &fx.basis,
        &"-o",
        &out,
    ]));
    assert!(error.contains("truncated"), "{error}");
    assert!(!out.exists());

    let error = failed(&tvf(&[
        &"compress",
        &fx.mesh,
        &fx.field,
        &"--basis",
        &fx.basis,
        &"--pairs",
        &"5000",
        &"-o",
        &file,
    ]));
    assert!(error.contains("5000 pairs requested"), "{error}");
}

#[test]
fn rate_distortion_writes_csv_and_plot() {
    let fx = fixture();
    let dir = fx.path("rd");
    let stdout = succeeded(&tvf(&[
        &"rate-distortion",
        &fx.mesh,
        &fx.field,
        &"--basis",
        &fx.basis,
        &"--pairs",
        &"10,20,40,80",
        &"--bits",
        &"8,12",
        &"-o",
        &dir,
    ]));
    assert!(stdout.contains("smaller"), "{stdout}");
    let csv = std::fs::read_to_string(dir.join("rate_distortion.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 4 * 3);
    let f64_errors: Vec<f64> = rows
        .iter()
        .filter(|r| r[0] == "f64")
        .map(|r| r[5].parse().unwrap())
        .collect();
    assert!(
        f64_errors.windows(2).all(|w| w[1] <= w[0]),
        "error must fall with k: {f64_errors:?}"
    );
    let png = std::fs::read(dir.join("rate_distortion.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
}

/// A basis file of eigenfunctions (`tvf basis -o`) is read in blocks by `filter` and
/// `coefficients`; the results are those of the same basis loaded whole (its fields layout) to
/// round-off (another summation order).
#[test]
fn filter_and_coefficients_read_an_eigenfunctions_file_in_blocks() {
    let fx = fixture();
    let (blocks, whole) = eigenfunctions_and_fields_files(&fx);
    let fields = FaceFields::new(&fx.loaded).unwrap();
    let mut filtered = Vec::new();
    for (basis, name) in [(&blocks, "blocks.npy"), (&whole, "whole.npy")] {
        let out = fx.path(name);
        let output = tvf(&[
            &"filter",
            &fx.mesh,
            &fx.field,
            &"--basis",
            basis,
            &"--integrable",
            &"lowpass:t=0.01",
            &"--rest",
            &"0",
            &"-o",
            &out,
        ]);
        succeeded(&output);
        let stderr = String::from_utf8_lossy(&output.stderr).to_string();
        assert_eq!(
            stderr.contains("read in blocks"),
            name == "blocks.npy",
            "{stderr}"
        );
        filtered.push(tangent(&fields, &out));
    }
    assert!(relative_error(&fields, &filtered[1], &filtered[0]) < 1e-12);
    let coefficients: Vec<Vec<f64>> = [&blocks, &whole]
        .iter()
        .map(|basis| {
            let output = tvf(&[
                &"coefficients",
                &fx.mesh,
                &fx.field,
                &"--basis",
                basis,
                &"--json",
            ]);
            let json: serde_json::Value = serde_json::from_str(&succeeded(&output)).unwrap();
            json["coefficients"]
                .as_array()
                .unwrap()
                .iter()
                .map(|entry| entry["coefficient"].as_f64().unwrap())
                .collect()
        })
        .collect();
    let scale = coefficients[1].iter().fold(0.0f64, |m, c| m.max(c.abs()));
    for (a, b) in coefficients[0].iter().zip(&coefficients[1]) {
        assert!((a - b).abs() <= 1e-12 * scale, "{a} against {b}");
    }
}

/// Writes a constraint file for the fixture's torus (576 faces, 288 vertices): two vectors, a
/// source and a vortex.
fn torus_constraints(path: &Path) {
    std::fs::write(
        path,
        r#"{"omega": 0.1, "constraints": [
 {"id": "v1", "kind": "vector", "face": 10, "value": [0.0, 1.0, 0.0]},
 {"id": "v2", "kind": "vector", "face": 300, "value": [1.0, 0.0, 0.0]},
 {"id": "source", "kind": "divergence", "vertex": 50, "value": 2.0},
 {"id": "vortex", "kind": "curl", "face": 200, "value": 2.0}]}"#,
    )
    .unwrap();
}

/// An eigenfunctions file of the fixture (`tvf basis -k 60 -o`) and the same basis loaded and
/// saved whole (the fields layout, which every command loads whole).
fn eigenfunctions_and_fields_files(fx: &Fixture) -> (PathBuf, PathBuf) {
    let blocks = fx.path("eigenfunctions.tvfb");
    succeeded(&tvf(&[
        &"basis", &fx.mesh, &"-k", &"60", &"--quiet", &"-o", &blocks,
    ]));
    let complex = Conforming::new(&fx.loaded, MassLumping::Barycentric).unwrap();
    let key = BasisFileKey::new(&fx.loaded, &complex);
    let whole = fx.path("fields.tvfb");
    let basis = tvf_spectral::load_basis(&blocks, &key, &complex).unwrap();
    save_basis(&whole, &basis, &key).unwrap();
    (blocks, whole)
}

/// The arguments of `compress` (20 pairs), `spline` and `design --reduced` of the fixture with
/// `basis`, writing `outputs` (in that order).
fn consumer_runs(
    fx: &Fixture,
    constraints: &Path,
    basis: &Path,
    outputs: [&Path; 3],
) -> [Vec<std::ffi::OsString>; 3] {
    let [compressed, spline, design] = outputs;
    let (mesh, field) = (fx.mesh.as_os_str(), fx.field.as_os_str());
    let constrained = ["--constraints".as_ref(), constraints.as_os_str()];
    let basis = ["--basis".as_ref(), basis.as_os_str()];
    let args = |parts: &[&std::ffi::OsStr]| parts.iter().map(|&p| p.to_owned()).collect();
    [
        args(
            &[
                &[
                    "compress".as_ref(),
                    mesh,
                    field,
                    "--pairs".as_ref(),
                    "20".as_ref(),
                ],
                &basis[..],
                &["-o".as_ref(), compressed.as_os_str()],
            ]
            .concat(),
        ),
        args(
            &[
                &["spline".as_ref(), mesh],
                &constrained[..],
                &basis[..],
                &["-o".as_ref(), spline.as_os_str()],
            ]
            .concat(),
        ),
        args(
            &[
                &["design".as_ref(), mesh, "--reduced".as_ref()],
                &constrained[..],
                &basis[..],
                &["-o".as_ref(), design.as_os_str()],
            ]
            .concat(),
        ),
    ]
}

/// Runs `tvf` with owned arguments.
fn tvf_owned(args: &[std::ffi::OsString]) -> Output {
    let args: Vec<&dyn AsRef<std::ffi::OsStr>> = args
        .iter()
        .map(|a| a as &dyn AsRef<std::ffi::OsStr>)
        .collect();
    tvf(&args)
}

/// `compress`, `spline` and `design --reduced` read an eigenfunctions file in blocks too (said
/// on stderr): a `.tvfc` made in blocks decodes with the basis loaded whole (the same basis id)
/// to the field of the whole basis's file to round-off (the coefficients' projection sums in
/// another order: 1e-13), and splines and soft designs equal the whole basis's to round-off
/// (their reduced systems are the same bit for bit; the synthesis sums in another order: 1e-13).
#[test]
fn compress_spline_and_design_read_an_eigenfunctions_file_in_blocks() {
    let fx = fixture();
    let (blocks, whole) = eigenfunctions_and_fields_files(&fx);
    let constraints = fx.path("c.json");
    torus_constraints(&constraints);
    let fields = FaceFields::new(&fx.loaded).unwrap();
    let mut solved = Vec::new();
    for (basis, name) in [(&blocks, "blocks"), (&whole, "whole")] {
        let compressed = fx.path(&format!("{name}.tvfc"));
        let spline = fx.path(&format!("{name}-spline.npy"));
        let design = fx.path(&format!("{name}-design.npy"));
        let runs = consumer_runs(&fx, &constraints, basis, [&compressed, &spline, &design]);
        for args in &runs {
            let output = tvf_owned(args);
            succeeded(&output);
            let stderr = String::from_utf8_lossy(&output.stderr).to_string();
            assert_eq!(
                stderr.contains("read in blocks"),
                name == "blocks",
                "{stderr}"
            );
        }
        let decoded = fx.path(&format!("{name}-decoded.npy"));
        succeeded(&tvf(&[
            &"decompress",
            &fx.mesh,
            &compressed,
            &"--basis",
            &whole,
            &"-o",
            &decoded,
        ]));
        solved.push([decoded, spline, design].map(|path| tangent(&fields, &path)));
    }
    for (what, (found, expected)) in ["decoded", "spline", "design"]
        .iter()
        .zip(solved[0].iter().zip(&solved[1]))
    {
        let error = relative_error(&fields, expected, found);
        assert!(error < 1e-13, "{what}: {error:e}");
    }
}

/// A truncated eigenfunctions file, and one with a payload bit flipped, are refused by
/// `compress`, `spline` and `design --reduced` with an error naming the file, and nothing is
/// written.
#[test]
fn damaged_eigenfunctions_files_are_refused_by_compress_spline_and_design() {
    let fx = fixture();
    let (blocks, _) = eigenfunctions_and_fields_files(&fx);
    let constraints = fx.path("c.json");
    torus_constraints(&constraints);
    let bytes = std::fs::read(&blocks).unwrap();
    let truncated = fx.path("truncated.tvfb");
    std::fs::write(&truncated, &bytes[..bytes.len() - 100]).unwrap();
    let mut flipped_bytes = bytes.clone();
    let at = bytes.len() - 200;
    flipped_bytes[at] ^= 0x01;
    let flipped = fx.path("flipped.tvfb");
    std::fs::write(&flipped, &flipped_bytes).unwrap();
    let out = fx.path("out");
    for (damaged, problem) in [(&truncated, "truncated"), (&flipped, "checksum")] {
        let runs = consumer_runs(&fx, &constraints, damaged, [&out, &out, &out]);
        for args in &runs {
            let output = tvf_owned(args);
            let stderr = String::from_utf8_lossy(&output.stderr).to_lowercase();
            assert!(!output.status.success(), "{stderr}");
            let name = damaged.file_name().unwrap().to_string_lossy().to_string();
            assert!(
                stderr.contains(&name) && stderr.contains(problem),
                "{stderr}"
            );
            assert!(!out.exists());
        }
    }
}
