//! `info.json` of a complex folder (`tvf operators MESH -o DIR`): what the files are, in which
//! numbering, and everything [`crate::read_complex_folder`] needs to rebuild the complex — the
//! node kinds, the sampling, the fixed nodes, the form of each mass, the boundary condition and
//! the mesh's fingerprint. `docs/discretizations.md` lists the keys.

use serde_json::{json, Map, Value};
use tvf_core::discretization::{
    HodgeComplex, HodgeOperators, Mass, MassForm, NodeKind, NodeSpace, SamplingReproduction,
};
use tvf_core::mesh::ValidationReport;
use tvf_core::SurfaceMesh;
use tvf_discretizations::MatrixSampling;

/// How the matrices of a complex folder are stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MatrixFileFormat {
    /// Matrix Market coordinate files (`NAME.mtx`, 1-based).
    MatrixMarket,
    /// `scipy.sparse.save_npz` files (`NAME.npz`, CSR).
    SparseNpz,
}

impl MatrixFileFormat {
    /// Both formats, in the order a folder is searched.
    pub const ALL: [MatrixFileFormat; 2] = [Self::MatrixMarket, Self::SparseNpz];

    /// The file extension, without the dot: `mtx`, `npz`.
    pub fn extension(self) -> &'static str {
        match self {
            Self::MatrixMarket => "mtx",
            Self::SparseNpz => "npz",
        }
    }

    /// What `info.json` says of the format.
    fn description(self) -> &'static str {
        match self {
            Self::MatrixMarket => "Matrix Market (.mtx)",
            Self::SparseNpz => "scipy.sparse CSR (.npz, scipy.sparse.load_npz)",
        }
    }
}

/// The file name (without extension) of mass `name` (`M0`, `M1`, `M2`) stored in `form`: the
/// name, with `_inverse` when the file holds the inverse (the form in which it is sparse).
pub fn mass_file_name(name: &str, form: MassForm) -> String {
    match form {
        MassForm::Direct => name.to_string(),
        MassForm::Inverse => format!("{name}_inverse"),
    }
}

/// How the fields of `complex` are sampled, as a [`MatrixSampling`]: face frames by the kind of
/// its field nodes; on edges (1-forms) Whitney interpolation, or polygonal DEC's per-face sharp
/// when the sampling states that it reproduces only linear gradients (what the sharp states and
/// Whitney interpolation, which reproduces constant vectors, does not); none if it samples no
/// fields or samples them through an intrinsic triangulation (which a folder does not hold).
pub fn sampling_of(complex: &dyn HodgeComplex) -> MatrixSampling {
    match (complex.sampling(), complex.field_nodes().kind) {
        (Some(_), NodeKind::FaceFrames) => MatrixSampling::FaceFrames,
        (Some(sampling), NodeKind::Edges) => match sampling.reproduction() {
            SamplingReproduction::LinearGradients => MatrixSampling::PolygonSharp,
            SamplingReproduction::ConstantVectors => MatrixSampling::Whitney,
            // On an intrinsic triangulation: no sampling the folder's matrices can rebuild.
            SamplingReproduction::Approximate => MatrixSampling::None,
        },
        _ => MatrixSampling::None,
    }
}

/// How many faces of each size `mesh` has, `{"3": triangles, "4": quads, …}`.
fn face_size_counts(mesh: &SurfaceMesh) -> Map<String, Value> {
    mesh.face_size_counts()
        .into_iter()
        .map(|(size, count)| (size.to_string(), json!(count)))
        .collect()
}

/// The `info.json` of the folder `tvf operators` writes for `complex` on `mesh` (loaded with
/// `report`): `not_written` lists the derived matrices left out and why.
pub fn complex_folder_info(
    complex: &dyn HodgeComplex,
    mesh: &SurfaceMesh,
    report: &ValidationReport,
    format: MatrixFileFormat,
    not_written: Map<String, Value>,
) -> Value {
    let (n0, n1, n2) = (
        complex.potential_dimension(),
        complex.field_dimension(),
        complex.co_potential_dimension(),
    );
    let spaces = [
        complex.potential_nodes(),
        complex.field_nodes(),
        complex.co_potential_nodes(),
    ];
    let mut masses = Map::new();
    for (name, mass) in [
        ("M0", complex.m0()),
        ("M1", complex.m1()),
        ("M2", complex.m2()),
    ] {
        masses.insert(
            name.to_string(),
            mass_info(&mass_file_name(name, mass.form()), mass),
        );
    }
    let fixed = |space: &NodeSpace| -> Vec<usize> {
        (0..space.len())
            .filter(|&i| space.dirichlet.get(i) == Some(&true))
            .collect()
    };
    let topology = complex.topology();
    json!({
        "discretization": complex.id(),
        "mesh_fingerprint": format!("{:016x}", mesh.fingerprint()),
        "mesh_kind": mesh.kind_name(),
        "face_sizes": face_size_counts(mesh),
        "vertices": mesh.vertex_count(),
        "input_vertices": report.input_vertex_count,
        "matrix_format": format.description(),
        "edges": mesh.edge_count(),
        "faces": mesh.face_count(),
        "components": mesh.component_count(),
        "genus": mesh.genus(),
        "harmonic_dimension": topology.harmonic_dimension,
        "closed": mesh.is_closed(),
        "boundary_condition": if topology.has_boundary {
            Value::from(topology.boundary_condition.name())
        } else {
            Value::Null
        },
        "sampling": sampling_of(complex).name(),
        "nodes": {
            "potentials": spaces[0].kind.name(),
            "fields": spaces[1].kind.name(),
            "co_potentials": spaces[2].kind.name(),
        },
        "fixed_nodes": {
            "about": "indices of the nodes the boundary condition fixes to zero: their columns of d0 (potentials), rows of d0 and columns of d1 (fields) or rows of d1 (co-potentials) are empty",
            "potentials": fixed(spaces[0]),
            "fields": fixed(spaces[1]),
            "co_potentials": fixed(spaces[2]),
        },
        "intrinsic_triangulation": complex.intrinsic_triangulation().map(|tri| json!({
            "about": "the complex is built on this intrinsic triangulation of the mesh (edge lengths only): intrinsic_faces.npy, intrinsic_edges.npy, intrinsic_edge_lengths.npy; its vertices are the mesh's, then the inserted ones",
            "vertices": tri.vertex_count(),
            "inserted_vertices": tri.inserted_vertex_count(),
            "edges": tri.edge_count(),
            "faces": tri.face_count(),
            "flips": tri.flip_count(),
        })),
        "matrices": matrix_descriptions(complex, [n0, n1, n2]),
        "masses": masses,
        "not_written": not_written,
        "conventions": conventions(report),
    })
}

/// What each matrix file holds.
fn matrix_descriptions(complex: &dyn HodgeComplex, [n0, n1, n2]: [usize; 3]) -> Value {
    json!({
        "d0": format!("{n1} x {n0}, gradient: potentials -> fields (pointwise)"),
        "d1": format!("{n2} x {n1}, integrated curl: fields -> co-potentials; d1 d0 = 0"),
        "M0": format!("{n0} x {n0}, potential mass (integrated, area)"),
        "M1": format!("{n1} x {n1}, field mass: x^T M1 y = integral of <x, y>"),
        "M2": format!("{n2} x {n2}, turns d1's integrated values into pointwise ones (1/area); M2^-1 is the co-potential mass"),
        "S0": format!("{n0} x {n0} potential stiffness d0^T M1 d0 (the cotan matrix for P1 potentials)"),
        "S2": format!("{n2} x {n2} co-potential stiffness d1 M1^-1 d1^T"),
        "S": format!("{n1} x {n1} Dirichlet energy M1 d0 M0^-1 d0^T M1 + d1^T M2 d1"),
        "B": format!("{n1} x {n1} biharmonic energy S M1^-1 S"),
        "J": if complex.rotation().is_some() {
            format!("{n1} x {n1}, +pi/2 rotation per face, (a, b) -> (-b, a)")
        } else {
            "not written: this discretization has no rotation of fields".to_string()
        },
        "read_back": "tvf --complex DIR reads d0, d1, M0, M1 and M2 (or M2_inverse) only: S0, S2, S, B and J are derived and ignored",
    })
}

/// The index, frame, edge and orientation conventions of the files.
fn conventions(report: &ValidationReport) -> Value {
    let dropped = report.unreferenced_vertices();
    json!({
        "indices": "0-based in this file, in .npz and .npy files; Matrix Market files are 1-based",
        "face_frames": "a face-frame field stores face t at rows 2t, 2t+1 in the frame e1 = normalize(p_i1 - p_i0), e2 = n x e1",
        "edges": "edges (a, b) with a < b in lexicographic order; a 1-form is the field integrated from a to b",
        "vertex_order": if dropped == 0 {
            format!("as in the input mesh ({} vertices, none unreferenced); vertex_map.npy is the identity", report.input_vertex_count)
        } else {
            format!(
                "the input's vertices in input order without the {dropped} unreferenced ones \
                 ({} of {} kept): vertex_map.npy[v] is the input index of mesh vertex v",
                report.original_vertex.len(),
                report.input_vertex_count
            )
        },
        "face_orientation": "counter-clockwise seen from outside, n = (p1 - p0) x (p2 - p0) normalized",
    })
}

/// What `info.json` says of a mass: its file, whether the file holds the mass or its inverse,
/// and whether it is diagonal.
fn mass_info(file: &str, mass: &Mass) -> Value {
    json!({
        "file": file,
        "form": mass.form().name(),
        "storage": if mass.is_diagonal() { "diagonal" } else { "sparse" },
    })
}
