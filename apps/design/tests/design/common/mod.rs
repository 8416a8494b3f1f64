//! Shared helpers for the tvf-design tests: meshes, bases and seeded constraints.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::{HodgeComplex, HodgeOperators, NodeKind, NodeSpace};
use tvf_core::TriangleMesh;
use tvf_design::{
    default_regularization, CompiledConstraint, Constraint, ConstraintAssembler, Location,
    OperatorFamily, ReducedBasis, SoftOptions, Target,
};
use tvf_discretizations::{Conforming, MassLumping};
use tvf_spectral::{compute_basis, BasisRequest, SpectralBasis};

/// Node `i` of `nodes` as a constraint location (a vertex or an edge key; a face for face
/// nodes).
pub fn node_location(nodes: &NodeSpace, i: usize) -> Location {
    match nodes.kind {
        NodeKind::Vertices => Location::Vertex(i),
        NodeKind::Edges => Location::Edge(i),
        NodeKind::Faces | NodeKind::FaceFrames => Location::Face {
            face: i,
            barycentric: None,
        },
    }
}

/// The `d` lowest eigenfields (`None`: the complete basis).
pub fn spectral_basis<H: HodgeComplex + ?Sized>(complex: &H, d: Option<usize>) -> SpectralBasis {
    let request = match d {
        Some(d) => BasisRequest::fields(d),
        None => BasisRequest::complete(),
    };
    compute_basis(complex, &request).expect("basis of a generated closed mesh")
}

/// The first `d` columns of a basis, row-major.
pub fn truncated(basis: &SpectralBasis, d: usize) -> ReducedBasis {
    let u = basis.fields();
    let n = u.nrows();
    let rows: Vec<f64> = (0..n)
        .flat_map(|r| (0..d).map(move |j| u[(r, j)]))
        .collect();
    let harmonic = basis.families()[..d]
        .iter()
        .map(|f| *f == tvf_spectral::FieldFamily::Harmonic)
        .collect();
    ReducedBasis::from_row_major(rows, n, basis.eigenvalues()[..d].to_vec(), harmonic)
        .expect("valid basis")
}

/// Seeded constraints of every kind, at well-separated random faces / vertices / edges of the
/// conforming complex (divergence at vertices, curl at edges, one of each at a point, one
/// divergence of the other family at a point).
pub fn mixed_constraints(mesh: &TriangleMesh, vectors: usize, seed: u64) -> Vec<Constraint> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::new();
    let mut faces: Vec<usize> = Vec::new();
    while faces.len() < vectors + 3 {
        let f = rng.random_range(0..mesh.face_count());
        if !faces.contains(&f) {
            faces.push(f);
        }
    }
    for (k, &f) in faces[..vectors].iter().enumerate() {
        let v = [
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        ];
        out.push(Constraint::new(
            format!("v{k}"),
            Target::Vector(v),
            Location::Face {
                face: f,
                barycentric: None,
            },
        ));
    }
    let vertex = mesh.faces()[faces[vectors]][0];
    out.push(Constraint::new(
        "source",
        Target::Divergence(2.0),
        Location::Vertex(vertex),
    ));
    let edge = mesh.face_edges()[faces[vectors + 1]][0];
    out.push(Constraint::new(
        "vortex",
        Target::Curl(-1.5),
        Location::Edge(edge),
    ));
    let point = Location::Face {
        face: faces[vectors + 2],
        barycentric: Some(vec![0.2, 0.3, 0.5]),
    };
    out.push(Constraint::new(
        "curl-point",
        Target::Curl(1.0),
        point.clone(),
    ));
    out.push(
        Constraint::new("div-other", Target::Divergence(-0.5), point)
            .with_family(OperatorFamily::Other),
    );
    out
}

/// `‖a − b‖_{M_X} / ‖b‖_{M_X}`.
pub fn relative_difference(a: &[f64], b: &[f64], mass: &[f64]) -> f64 {
    let diff: f64 = a
        .iter()
        .zip(b)
        .zip(mass)
        .map(|((x, y), m)| m * (x - y) * (x - y))
        .sum();
    let norm: f64 = b.iter().zip(mass).map(|(y, m)| m * y * y).sum();
    (diff / norm).sqrt()
}

/// The inputs of a full soft design on `mesh` (conforming, barycentric, ω = 0.1): the Dirichlet
/// energy `S`, the diagonal of `M_X`, the options, and two seeded constraint sets with `vectors`
/// vector constraints each (seeds `seeds.0` and `seeds.1`).
pub struct FullDesignInputs {
    pub dirichlet: sprs::CsMat<f64>,
    pub mass: Vec<f64>,
    pub options: SoftOptions,
    pub first: Vec<CompiledConstraint>,
    pub second: Vec<CompiledConstraint>,
}

impl FullDesignInputs {
    pub fn new(mesh: &TriangleMesh, vectors: usize, seeds: (u64, u64)) -> Self {
        let complex = Conforming::new(mesh, MassLumping::Barycentric).expect("complex");
        let dirichlet = complex.dirichlet_energy().as_sparse().unwrap().clone();
        let options = SoftOptions {
            omega: 0.1,
            regularization: default_regularization(&complex),
        };
        let assembler = ConstraintAssembler::new(&complex, mesh);
        let compile = |seed| {
            assembler
                .compile_all(&mixed_constraints(mesh, vectors, seed))
                .expect("constraints")
        };
        Self {
            first: compile(seeds.0),
            second: compile(seeds.1),
            mass: complex.m1().diagonal_values().unwrap().to_vec(),
            dirichlet,
            options,
        }
    }
}

/// `max |a − b| / max |b|`.
pub fn max_relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}
