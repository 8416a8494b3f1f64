//! Property-based fuzzing of the OBJ, OFF and PLY readers: random bytes and mutated valid files
//! never panic, and whatever loads is a valid mesh.
//!
//! Cases per property: 256 by default; set `TVF_FUZZ_CASES` for a longer run, e.g.
//! `TVF_FUZZ_CASES=200000 cargo test --release -p tvf-core --test mesh reader_fuzz`.

use proptest::prelude::*;
use tvf_core::generate::{genus_surface, icosphere};
use tvf_core::io::{parse_mesh_bytes, write_obj, write_ply, MeshFormat};
use tvf_core::TriangleMesh;

const FORMATS: [MeshFormat; 3] = [MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply];

fn config() -> ProptestConfig {
    let cases = std::env::var("TVF_FUZZ_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(256);
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Parses `bytes` in `format`; if it loads, checks the result is a consistent mesh.
fn parse_and_check(bytes: &[u8], format: MeshFormat) {
    match parse_mesh_bytes(bytes, format, "fuzz") {
        Ok(loaded) => {
            let mesh = &loaded.mesh;
            assert!(mesh.face_count() > 0);
            assert!((0..mesh.face_count())
                .flat_map(|f| mesh.face(f))
                .all(|&v| v < mesh.vertex_count()));
            assert!(mesh.positions().iter().flatten().all(|x| x.is_finite()));
            assert_eq!(loaded.report.original_vertex.len(), mesh.vertex_count());
            assert!(loaded.report.min_angle_deg > 0.0);
        }
        Err(error) => assert!(error.to_string().starts_with("fuzz")),
    }
}

/// Valid seed files of every format and encoding (built once).
fn seeds() -> Vec<(Vec<u8>, MeshFormat)> {
    static SEEDS: std::sync::OnceLock<Vec<(Vec<u8>, MeshFormat)>> = std::sync::OnceLock::new();
    SEEDS.get_or_init(build_seeds).clone()
}

fn build_seeds() -> Vec<(Vec<u8>, MeshFormat)> {
    let dir = tempfile::tempdir().expect("temporary directory");
    let mesh = genus_surface(1, 2);
    let obj = dir.path().join("seed.obj");
    let ply = dir.path().join("seed.ply");
    write_obj(&obj, &mesh).expect("write OBJ seed");
    write_ply(&ply, &icosphere(0)).expect("write PLY seed");
    let mut seeds = vec![
        (std::fs::read(&obj).unwrap(), MeshFormat::Obj),
        (std::fs::read(&ply).unwrap(), MeshFormat::Ply),
        (off_text(&icosphere(0)).into_bytes(), MeshFormat::Off),
        (ascii_ply(&icosphere(0)).into_bytes(), MeshFormat::Ply),
    ];
    seeds.push((
        b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\ng a\nf 1/1 2/1 3/1\nf -4 -2 -1\n".to_vec(),
        MeshFormat::Obj,
    ));
    seeds
}

fn off_text(mesh: &TriangleMesh) -> String {
    let mut text = format!("OFF\n{} {} 0\n", mesh.vertex_count(), mesh.face_count());
    for p in mesh.positions() {
        text += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for f in mesh.faces() {
        text += &format!("3 {} {} {}\n", f[0], f[1], f[2]);
    }
    text
}

fn ascii_ply(mesh: &TriangleMesh) -> String {
    let mut text = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.vertex_count(),
        mesh.face_count()
    );
    for p in mesh.positions() {
        text += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for f in mesh.faces() {
        text += &format!("3 {} {} {}\n", f[0], f[1], f[2]);
    }
    text
}

/// One edit of a byte string.
#[derive(Debug, Clone)]
enum Mutation {
    /// Replace the byte at a relative position.
    Set(f64, u8),
    /// Insert bytes at a relative position.
    Insert(f64, Vec<u8>),
    /// Delete a range (relative start, length).
    Delete(f64, usize),
    /// Cut the file at a relative position.
    Truncate(f64),
    /// Copy a range to another place (relative source, length, relative target).
    Duplicate(f64, usize, f64),
    /// Replace a range with an interesting token.
    Token(f64, usize),
}

const TOKENS: &[&str] = &[
    "0",
    "-1",
    "nan",
    "inf",
    "-0",
    "1e308",
    "4294967295",
    "18446744073709551616",
    " ",
    "\n",
    "f",
    "v",
    "#",
    "/",
    "//",
    "3",
    "255",
    "end_header\n",
    "element face 99999999999\n",
];

fn mutation() -> impl Strategy<Value = Mutation> {
    let at = 0.0..1.0f64;
    prop_oneof![
        (at.clone(), any::<u8>()).prop_map(|(p, b)| Mutation::Set(p, b)),
        (at.clone(), prop::collection::vec(any::<u8>(), 1..8))
            .prop_map(|(p, b)| Mutation::Insert(p, b)),
        (at.clone(), 1..64usize).prop_map(|(p, n)| Mutation::Delete(p, n)),
        at.clone().prop_map(Mutation::Truncate),
        (at.clone(), 1..64usize, at.clone()).prop_map(|(p, n, q)| Mutation::Duplicate(p, n, q)),
        (at, 0..TOKENS.len()).prop_map(|(p, t)| Mutation::Token(p, t)),
    ]
}

fn apply(bytes: &mut Vec<u8>, mutation: &Mutation) {
    let index = |p: f64, len: usize| ((p * len as f64) as usize).min(len);
    match mutation {
        Mutation::Set(p, b) => {
            if !bytes.is_empty() {
                let i = index(*p, bytes.len() - 1);
                bytes[i] = *b;
            }
        }
        Mutation::Insert(p, new) => {
            let i = index(*p, bytes.len());
            bytes.splice(i..i, new.iter().copied());
        }
        Mutation::Delete(p, n) => {
            let i = index(*p, bytes.len());
            let end = (i + n).min(bytes.len());
            bytes.drain(i..end);
        }
        Mutation::Truncate(p) => bytes.truncate(index(*p, bytes.len())),
        Mutation::Duplicate(p, n, q) => {
            let i = index(*p, bytes.len());
            let end = (i + n).min(bytes.len());
            let piece = bytes[i..end].to_vec();
            let j = index(*q, bytes.len());
            bytes.splice(j..j, piece);
        }
        Mutation::Token(p, t) => {
            let i = index(*p, bytes.len());
            let end = (i + 1).min(bytes.len());
            bytes.splice(i..end, TOKENS[*t].bytes());
        }
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        for format in FORMATS {
            parse_and_check(&bytes, format);
        }
    }

    #[test]
    fn random_text_never_panics(text in "(v|f|vt|#|OFF|ply|element|property|list|end_header|[ 0-9.\\-/\n]){0,120}") {
        for format in FORMATS {
            parse_and_check(text.as_bytes(), format);
        }
    }

    #[test]
    fn mutated_valid_files_never_panic(
        seed in 0..5usize,
        mutations in prop::collection::vec(mutation(), 1..6),
        as_other_format in 0..4usize,
    ) {
        let (mut bytes, format) = seeds()[seed].clone();
        for m in &mutations {
            apply(&mut bytes, m);
        }
        // Also feed each file to the other readers now and then.
        let format = if as_other_format < 3 { format } else { FORMATS[seed % 3] };
        parse_and_check(&bytes, format);
    }
}

#[test]
fn unmutated_seeds_load() {
    for (bytes, format) in seeds() {
        let loaded = parse_mesh_bytes(&bytes, format, "seed").unwrap();
        assert!(loaded.mesh.face_count() > 0);
    }
}
