//! `tvf decompress` and `tvf rate-distortion` read a basis file of eigenfunctions in blocks (said
//! on stderr): a field or a sequence decoded in blocks is the one decoded with the same basis
//! loaded whole, bit for bit (a diagonal `M1`: the same fields added in the same order), and a
//! rate–distortion curve has the same file sizes and its errors to `1e-12` relative (the
//! projection sums in another order). With a non-diagonal `M1` whose co-potentials do not fit one
//! block (`$TVF_BASIS_BLOCK_BYTES` made small), `compress` and `decompress` load the basis whole
//! instead, with a note, so that files made either way decode either way. Damaged basis files
//! are refused naming the file, with nothing written (also by `edit`, which reads a basis file
//! on demand).

use super::common::{assert_success, output_within, tvf, write_field};
use std::path::{Path, PathBuf};
use std::process::Output;
use tvf_core::generate::torus;
use tvf_core::io::{load_mesh, write_obj};
use tvf_core::TriangleMesh;
use tvf_spectral::{read_face_vector_sequence, write_face_vector_sequence, NpyDtype};

/// A torus (written as OBJ and read back), a field of it and a sequence of 18 frames (two
/// decoding groups).
struct Fixture {
    dir: tempfile::TempDir,
    mesh: PathBuf,
    field: PathBuf,
    frames: PathBuf,
}

impl Fixture {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        let mesh = dir.path().join("torus.obj");
        write_obj(&mesh, &torus(1.0, 0.45, 24, 12).unwrap()).unwrap();
        let loaded: TriangleMesh = load_mesh(&mesh).unwrap().mesh.into_triangles().unwrap();
        let field = dir.path().join("field.txt");
        write_field(&loaded, &field);
        let vectors = tvf_spectral::read_face_vectors(&field).unwrap();
        let frames: Vec<Vec<[f64; 3]>> = (0..18)
            .map(|t| {
                let turn = 0.1 * t as f64;
                let (c, s) = (turn.cos(), turn.sin());
                vectors
                    .iter()
                    .map(|v| [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]])
                    .collect()
            })
            .collect();
        let frames_path = dir.path().join("frames.npy");
        write_face_vector_sequence(&frames_path, &frames, NpyDtype::F64).unwrap();
        Self {
            dir,
            mesh,
            field,
            frames: frames_path,
        }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// A basis file of eigenfunctions (`tvf basis -k 60`, `args` added) named `name`.
    fn basis(&self, name: &str, args: &[&str]) -> PathBuf {
        let path = self.path(name);
        let output = tvf()
            .arg("basis")
            .arg(&self.mesh)
            .args(["-k", "60", "--quiet"])
            .args(args)
            .arg("-o")
            .arg(&path)
            .output()
            .unwrap();
        assert_success(&output);
        path
    }
}

/// Runs `tvf COMMAND MESH INPUT --basis BASIS ARGS -o OUT` with `$TVF_BASIS_BLOCK_BYTES` set to
/// `block_bytes` if given.
fn run(
    fx: &Fixture,
    command: &str,
    input: &Path,
    basis: &Path,
    args: &[&str],
    out: &Path,
    block_bytes: Option<&str>,
) -> Output {
    let mut run = tvf();
    run.arg(command)
        .arg(&fx.mesh)
        .arg(input)
        .arg("--basis")
        .arg(basis)
        .args(args)
        .arg("-o")
        .arg(out);
    if let Some(bytes) = block_bytes {
        run.env("TVF_BASIS_BLOCK_BYTES", bytes);
    }
    run.output().unwrap()
}

/// stderr of a run that succeeded.
#[track_caller]
fn stderr_of(output: &Output) -> String {
    assert_success(output);
    String::from_utf8_lossy(&output.stderr).to_string()
}

/// The same basis in the fields layout (loaded whole by every command): `tvf basis --export`
/// writes the fields, not the eigenfunctions.
fn whole_copy(fx: &Fixture, eigenfunctions: &Path, name: &str) -> PathBuf {
    let mesh = load_mesh(&fx.mesh).unwrap().mesh.into_triangles().unwrap();
    let complex =
        tvf_discretizations::Conforming::new(&mesh, tvf_discretizations::MassLumping::Barycentric)
            .unwrap();
    let key = tvf_spectral::BasisFileKey::new(&mesh, &complex);
    let basis = tvf_spectral::load_basis(eigenfunctions, &key, &complex).unwrap();
    let path = fx.path(name);
    tvf_spectral::save_basis(&path, &basis, &key).unwrap();
    path
}

#[test]
fn decompress_and_rate_distortion_read_a_basis_file_in_blocks() {
    let fx = Fixture::new();
    let blocks = fx.basis("blocks.tvfb", &[]);
    let whole = whole_copy(&fx, &blocks, "whole.tvfb");
    let compressed = fx.path("frames.tvfc");
    let args = ["--pairs", "20", "--bits", "12"];
    let stderr = stderr_of(&run(
        &fx,
        "compress",
        &fx.frames,
        &blocks,
        &args,
        &compressed,
        None,
    ));
    assert!(stderr.contains("read in blocks"), "{stderr}");
    let mut decoded = Vec::new();
    for (basis, name) in [(&blocks, "blocks"), (&whole, "whole")] {
        let out = fx.path(&format!("{name}-decoded.npy"));
        let stderr = stderr_of(&run(&fx, "decompress", &compressed, basis, &[], &out, None));
        assert_eq!(
            stderr.contains("read in blocks"),
            name == "blocks",
            "{stderr}"
        );
        decoded.push(read_face_vector_sequence(&out).unwrap());
    }
    assert_eq!(decoded[0].len(), 18);
    assert_eq!(
        decoded[0], decoded[1],
        "decoded in blocks = loaded whole, bit for bit"
    );

    let mut curves = Vec::new();
    for (basis, name) in [(&blocks, "blocks"), (&whole, "whole")] {
        let out = fx.path(&format!("{name}-rd"));
        let args = ["--pairs", "5,10,25", "--bits", "8,16"];
        let stderr = stderr_of(&run(
            &fx,
            "rate-distortion",
            &fx.field,
            basis,
            &args,
            &out,
            None,
        ));
        assert_eq!(
            stderr.contains("read in blocks"),
            name == "blocks",
            "{stderr}"
        );
        curves.push(std::fs::read_to_string(out.join("rate_distortion.csv")).unwrap());
    }
    let rows = |csv: &str| -> Vec<Vec<String>> {
        csv.lines()
            .skip(1)
            .map(|l| l.split(',').map(str::to_string).collect())
            .collect()
    };
    let (found, expected) = (rows(&curves[0]), rows(&curves[1]));
    assert_eq!(found.len(), 9);
    for (found, expected) in found.iter().zip(&expected) {
        let last = found.len() - 1;
        assert_eq!(found[..last], expected[..last], "coding, pairs and sizes");
        let (a, b): (f64, f64) = (
            found[last].parse().unwrap(),
            expected[last].parse().unwrap(),
        );
        assert!((a - b).abs() <= 1e-12 * b, "error {a} against {b}");
    }
}

/// A Galerkin `M1` (non-diagonal) read in blocks of 4 KiB: the co-potentials do not fit one
/// block, so `compress` and `decompress` load the basis whole (noted); a file made so decodes in
/// blocks (the default size holds them all) and the other way round, to `1e-13`.
#[test]
fn a_non_diagonal_mass_in_small_blocks_is_loaded_whole_for_the_basis_id() {
    let fx = Fixture::new();
    let basis = fx.basis("galerkin.tvfb", &["--discretization", "whitney-galerkin"]);
    let small = Some("4096");
    let mut decoded = Vec::new();
    for (compress_blocks, decompress_blocks) in [(small, None), (None, small)] {
        let compressed = fx.path("g.tvfc");
        let _ = std::fs::remove_file(&compressed);
        let args = ["--pairs", "20"];
        let stderr = stderr_of(&run(
            &fx,
            "compress",
            &fx.field,
            &basis,
            &args,
            &compressed,
            compress_blocks,
        ));
        assert_eq!(
            stderr.contains("loaded whole"),
            compress_blocks.is_some(),
            "{stderr}"
        );
        let out = fx.path("g.npy");
        let _ = std::fs::remove_file(&out);
        let stderr = stderr_of(&run(
            &fx,
            "decompress",
            &compressed,
            &basis,
            &[],
            &out,
            decompress_blocks,
        ));
        assert_eq!(
            stderr.contains("loaded whole"),
            decompress_blocks.is_some(),
            "{stderr}"
        );
        decoded.push(tvf_spectral::read_face_vectors(&out).unwrap());
    }
    let scale = decoded[1]
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    for (a, b) in decoded[0].iter().flatten().zip(decoded[1].iter().flatten()) {
        assert!((a - b).abs() <= 1e-13 * scale, "{a} against {b}");
    }
    // A block size that is not a number of bytes is refused, naming the variable.
    let output = run(
        &fx,
        "compress",
        &fx.field,
        &basis,
        &["--pairs", "20"],
        &fx.path("x"),
        Some("lots"),
    );
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("TVF_BASIS_BLOCK_BYTES"));
    assert!(!fx.path("x").exists());
}

/// Cut short, or a payload bit flipped: `decompress` and `rate-distortion` refuse the basis file
/// naming it and the problem, and write nothing; `edit` refuses it before serving.
#[test]
fn damaged_basis_files_are_refused_by_decompress_and_rate_distortion() {
    let fx = Fixture::new();
    let basis = fx.basis("good.tvfb", &[]);
    let compressed = fx.path("c.tvfc");
    stderr_of(&run(
        &fx,
        "compress",
        &fx.field,
        &basis,
        &["--pairs", "20"],
        &compressed,
        None,
    ));
    let bytes = std::fs::read(&basis).unwrap();
    let truncated = fx.path("truncated.tvfb");
    std::fs::write(&truncated, &bytes[..bytes.len() - 100]).unwrap();
    let mut flipped_bytes = bytes.clone();
    flipped_bytes[bytes.len() - 200] ^= 0x01;
    let flipped = fx.path("flipped.tvfb");
    std::fs::write(&flipped, &flipped_bytes).unwrap();
    let out = fx.path("out");
    for (damaged, problem) in [(&truncated, "truncated"), (&flipped, "checksum")] {
        let name = damaged.file_name().unwrap().to_string_lossy().to_string();
        for (command, input, args) in [
            ("decompress", &compressed, &[][..]),
            ("rate-distortion", &fx.field, &["--pairs", "5,10"][..]),
        ] {
            let output = run(&fx, command, input, damaged, args, &out, None);
            let stderr = String::from_utf8_lossy(&output.stderr).to_lowercase();
            assert!(!output.status.success(), "{command}: {stderr}");
            assert!(
                stderr.contains(&name) && stderr.contains(problem),
                "{command}: {stderr}"
            );
            assert!(!out.exists(), "{command} wrote {}", out.display());
        }
        let mut edit = tvf();
        edit.arg("edit").arg(&fx.mesh).arg("--basis").arg(damaged);
        let output = output_within(&mut edit, 120);
        let stderr = String::from_utf8_lossy(&output.stderr).to_lowercase();
        assert!(!output.status.success(), "edit: {stderr}");
        assert!(
            stderr.contains(&name) && stderr.contains(problem),
            "edit: {stderr}"
        );
    }
}
