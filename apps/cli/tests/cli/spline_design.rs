//! End-to-end: `tvf spline` and `tvf design` on a generated genus-1 mesh written to an OBJ file:
//! output files, printed residuals, and errors naming the constraint file. Runs are case tables:
//! what each writes and prints, and how each refused run fails.

use std::path::Path;
use std::process::{Command, Output};
use tvf_core::generate::genus_surface;
use tvf_core::io::write_obj;
use tvf_spectral::read_face_vectors;

const CONSTRAINTS: &str = r#"{"omega": 0.1, "constraints": [
  {"id": "east", "kind": "vector", "face": 12, "value": [1, 0, 0]},
  {"id": "north", "kind": "vector", "face": 100, "barycentric": [0.2, 0.3, 0.5], "value": [0, 1, 0]},
  {"id": "source", "kind": "divergence", "vertex": 40, "value": 2.0, "weight": 5},
  {"id": "vortex", "kind": "curl", "edge": 77, "value": -1.0},
  {"id": "swirl", "kind": "curl", "face": 150, "barycentric": [0.3, 0.3, 0.4], "value": 1.0}]}"#;

/// A face the genus-1 test mesh does not have.
const FAR: &str =
    r#"{"constraints": [{"id": "far", "kind": "vector", "face": 999999, "value": [1, 0, 0]}]}"#;

/// Two vector constraints on one face: conflicting hard constraints.
const TWICE: &str = r#"{"constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [1, 0, 0]},
                            {"id": "b", "kind": "vector", "face": 3, "value": [0, 1, 0]}]}"#;

/// The test mesh `ring.obj` and the constraint files `c.json` (CONSTRAINTS), `bad.json` (FAR)
/// and `twice.json` (TWICE) in `dir`; returns the mesh's face count.
fn setup(dir: &Path) -> usize {
    let mesh = genus_surface(1, 4);
    write_obj(dir.join("ring.obj"), &mesh).expect("write mesh");
    for (name, text) in [
        ("c.json", CONSTRAINTS),
        ("bad.json", FAR),
        ("twice.json", TWICE),
    ] {
        std::fs::write(dir.join(name), text).expect("write constraints");
    }
    mesh.face_count()
}

/// `tvf SUBCOMMAND ring.obj --constraints FILE ARGS… -o OUTPUT` in `dir` (with `env` set).
fn run(dir: &Path, args: &[&str], constraints: &str, output: &str, env: &[(&str, &str)]) -> Output {
    let (subcommand, rest) = args.split_first().expect("a subcommand");
    Command::new(env!("CARGO_BIN_EXE_tvf"))
        .current_dir(dir)
        .args([subcommand, &"ring.obj", &"--constraints", &constraints])
        .args(rest)
        .args(["-o", output])
        .envs(env.iter().copied())
        .output()
        .expect("the tvf binary runs")
}

/// The relative residual printed for constraint `id`.
fn printed_residual(stdout: &str, id: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.split_whitespace().next() == Some(id))
        .unwrap_or_else(|| panic!("no residual line for {id} in:\n{stdout}"));
    line.split_whitespace()
        .nth(2)
        .and_then(|v| v.parse().ok())
        .expect("relative residual")
}

/// A run that writes a field: its arguments (after the mesh and `c.json`), its output file, what
/// its report names, and the residuals it must print.
struct Writing {
    args: &'static [&'static str],
    output: &'static str,
    reports: &'static [&'static str],
    residuals: Residuals,
}

/// What the printed residuals of a run must be.
enum Residuals {
    /// Hard constraints: every constraint met to 1e-9.
    Met,
    /// Soft constraints: the vector and curl ones finite, not all met exactly.
    Soft,
    /// Not checked by this run (another run of the same solver checks them).
    Unchecked,
}

const WRITING: &[Writing] = &[
    Writing {
        args: &["spline", "-k", "400"],
        output: "spline.npy",
        reports: &["spline setup", "spline solve"],
        residuals: Residuals::Met,
    },
    Writing {
        args: &["design", "--full"],
        output: "full.npy",
        reports: &["full factor", "system residual"],
        residuals: Residuals::Soft,
    },
    Writing {
        args: &["design", "--reduced", "-k", "400"],
        output: "reduced.txt",
        reports: &["reduced factor", "reduced solve"],
        residuals: Residuals::Unchecked,
    },
    Writing {
        args: &["design", "--full", "--ordering", "amd"],
        output: "amd.npy",
        reports: &["amd ordering", "rounding floor"],
        residuals: Residuals::Soft,
    },
    Writing {
        args: &["design", "--full", "--ordering", "nd"],
        output: "nd.npy",
        reports: &["nd ordering", "rounding floor"],
        residuals: Residuals::Soft,
    },
];

/// Every writing run succeeds, reports its steps and residuals and writes one finite vector
/// per face; both orderings of the full design give the same field.
#[test]
fn spline_and_design_write_fields_and_report_residuals() {
    let dir = tempfile::tempdir().unwrap();
    let faces = setup(dir.path());
    for case in WRITING {
        let output = run(dir.path(), case.args, "c.json", case.output, &[]);
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(
            output.status.success(),
            "{:?}: {stdout}\n{}",
            case.args,
            String::from_utf8_lossy(&output.stderr)
        );
        for step in case.reports {
            assert!(
                stdout.contains(step),
                "{:?}: no '{step}' in {stdout}",
                case.args
            );
        }
        match case.residuals {
            Residuals::Met => {
                for id in ["east", "north", "source", "vortex", "swirl"] {
                    assert!(printed_residual(&stdout, id) < 1e-9, "{id}: {stdout}");
                }
            }
            Residuals::Soft => {
                let soft: Vec<f64> = ["east", "north", "vortex"]
                    .iter()
                    .map(|id| printed_residual(&stdout, id))
                    .collect();
                assert!(
                    soft.iter().all(|r| r.is_finite()) && soft.iter().any(|&r| r > 1e-4),
                    "{:?}: {stdout}",
                    case.args
                );
            }
            Residuals::Unchecked => {}
        }
        let vectors = read_face_vectors(&dir.path().join(case.output)).expect("F×3 field");
        assert_eq!(vectors.len(), faces, "{:?}", case.args);
        assert!(vectors.iter().flatten().all(|x| x.is_finite()));
    }
    // Constraint "east" is met: the tangent part of (1, 0, 0) at face 12.
    let spline = read_face_vectors(&dir.path().join("spline.npy")).unwrap();
    assert!(spline[12].iter().map(|x| x * x).sum::<f64>() > 0.0);
    let [amd, nd] = ["amd.npy", "nd.npy"].map(|f| read_face_vectors(&dir.path().join(f)).unwrap());
    let scale = nd.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    for (a, b) in amd.iter().flatten().zip(nd.iter().flatten()) {
        assert!((a - b).abs() <= 1e-9 * scale, "{a} vs {b}");
    }
}

/// A run that is refused: its arguments (after the mesh), constraint file and environment, the
/// exit code and what the message names.
struct Refused {
    args: &'static [&'static str],
    constraints: &'static str,
    env: &'static [(&'static str, &'static str)],
    code: i32,
    names: &'static [&'static str],
}

const REFUSED: &[Refused] = &[
    // An ordering that does not exist, and one for the reduced design (which has none).
    Refused {
        args: &["design", "--full", "--ordering", "colamd"],
        constraints: "c.json",
        env: &[],
        code: 2,
        names: &["--ordering"],
    },
    Refused {
        args: &["design", "--reduced", "--ordering", "amd"],
        constraints: "c.json",
        env: &[],
        code: 2,
        names: &["--ordering"],
    },
    // Bad constraint files: the file and the constraint named.
    Refused {
        args: &["spline", "-k", "400"],
        constraints: "bad.json",
        env: &[],
        code: 1,
        names: &["bad.json", "'far'", "out of range"],
    },
    Refused {
        args: &["spline", "-k", "400"],
        constraints: "twice.json",
        env: &[],
        code: 1,
        names: &["'b'", "conflicting", "\"a\""],
    },
    // A malformed thread limit: the variable and its value named.
    Refused {
        args: &["design", "--full"],
        constraints: "c.json",
        env: &[("TVF_SEQUENTIAL_FLOP_LIMIT", "1e11x")],
        code: 1,
        names: &["TVF_SEQUENTIAL_FLOP_LIMIT", "1e11x"],
    },
    // A malformed memory budget of the eigensolver's slices: the variable and its value named.
    Refused {
        args: &["spline", "-k", "400"],
        constraints: "c.json",
        env: &[("TVF_SLICE_MEMORY", "4X")],
        code: 1,
        names: &["TVF_SLICE_MEMORY", "4X"],
    },
];

/// Every refused run exits with its code, names what is wrong, and writes no field.
#[test]
fn refused_runs_name_the_problem_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    setup(dir.path());
    for case in REFUSED {
        let output = run(dir.path(), case.args, case.constraints, "x.npy", case.env);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(
            output.status.code(),
            Some(case.code),
            "{:?}: {stderr}",
            case.args
        );
        for name in case.names {
            assert!(
                stderr.contains(name),
                "{:?}: no {name} in {stderr}",
                case.args
            );
        }
        assert!(!dir.path().join("x.npy").exists(), "{:?}", case.args);
    }
}
