//! [`MatrixComplex`]: a complex made of five matrices someone else assembled (a researcher's own
//! discretization, e.g. from Python or a folder of matrix files), checked before anything
//! downstream sees it.

use crate::face_fields::FaceFields;
use crate::face_geometry::FaceGeometry;
use crate::matrix_complex_nodes::{
    implied_harmonic_dimension, kind_size, matrix_node_spaces, FixedNodes, StatedNodeKinds,
};
use crate::nodal_evaluation::NodalEvaluation;
use crate::polygon_operators::PolygonOperators;
use crate::polygon_sampling::PolygonSampling;
use crate::whitney_sampling::WhitneySampling;
use sprs::CsMat;
use tvf_core::discretization::check_length;
use tvf_core::discretization::sparse::product;
use tvf_core::discretization::{
    BoundaryCondition, ComplexParts, DiscretizationError, FieldRotation, FieldSampling,
    HodgeComplex, Mass, NodeKind, NodeSpace, PointEvaluation,
};
use tvf_core::SurfaceMesh;

/// `max |d1 d0|` above this times `max |d1| · max |d0|` is not a complex.
pub const COMPLEX_TOLERANCE: f64 = 1e-10;

/// How the fields of a [`MatrixComplex`] become 3D vectors, if at all.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MatrixSampling {
    /// No sampling: the complex gives matrices, spectra and decompositions of coefficient
    /// vectors, nothing that needs vectors in space (splines, face vectors).
    None,
    /// Fields are piecewise-constant face vectors, `(x[2t], x[2t+1])` in the frame of face `t`
    /// (`e1 = normalize(p1 − p0)`, `e2 = n × e1`): `n1 = 2F`; also gives the rotation `J`.
    FaceFrames,
    /// Fields are primal 1-forms (one integral per edge, from `a` to `b`, `a < b`), sampled by
    /// Whitney interpolation: `n1 = E` (triangle meshes).
    Whitney,
    /// Fields are primal 1-forms sampled by polygonal DEC's sharp, one vector per face
    /// ([`crate::PolygonSampling`]): `n1 = E` (triangle and polygon meshes).
    PolygonSharp,
}

impl MatrixSampling {
    /// The kind of field nodes this sampling needs, if it needs any.
    pub fn field_kind(self) -> Option<NodeKind> {
        match self {
            Self::None => None,
            Self::FaceFrames => Some(NodeKind::FaceFrames),
            Self::Whitney | Self::PolygonSharp => Some(NodeKind::Edges),
        }
    }
}

impl MatrixSampling {
    /// Its name: `none`, `face-frames`, `whitney`.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::FaceFrames => "face-frames",
            Self::Whitney => "whitney",
            Self::PolygonSharp => "polygon-sharp",
        }
    }

    /// The sampling named `name`: `none`, `face-frames`, `whitney` or `polygon-sharp`.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "none" => Some(Self::None),
            "face-frames" => Some(Self::FaceFrames),
            "whitney" => Some(Self::Whitney),
            "polygon-sharp" => Some(Self::PolygonSharp),
            _ => None,
        }
    }
}

/// What samples the fields of a [`MatrixComplex`].
enum Sampler {
    None,
    FaceFrames(FaceFields),
    Whitney(WhitneySampling),
    PolygonSharp(PolygonSampling),
}

/// The five matrices of a complex: `d0` (`n1 × n0`), `d1` (`n2 × n1`) and the masses `M0`,
/// `M1`, `M2` (each a [`Mass`]: a diagonal, a sparse matrix, or for `M2` also the sparse
/// inverse).
pub struct ComplexMatrices {
    /// The gradient, potentials → fields.
    pub d0: CsMat<f64>,
    /// The integrated curl, fields → co-potentials.
    pub d1: CsMat<f64>,
    /// The potential mass.
    pub m0: Mass,
    /// The field mass.
    pub m1: Mass,
    /// `M2` (or its inverse, the co-potential mass).
    pub m2: Mass,
}

/// A [`HodgeComplex`] from five matrices ([`ComplexMatrices`]) on a mesh, with the nodes a
/// boundary condition fixes ([`FixedNodes`]) on a mesh with boundary. The node kind of each
/// space is the one stated ([`StatedNodeKinds`]; the field nodes a sampling needs are stated by
/// it when the size fits), else the one kind of its size (`V` vertices, `E` edges, `F` faces, `2F` face frames; a
/// size several kinds share, `V = F` on a quad torus, is an error asking for the kind); node
/// positions and components come from the mesh, and which constants lie in the kernel of each
/// stiffness from the matrices ([`crate::matrix_complex_nodes`]).
/// [`MatrixComplex::with_boundary`] checks everything the seam promises: shapes, finite entries,
/// fixed nodes with empty rows and columns, masses symmetric positive definite on the free nodes
/// (a diagonal may be zero where no face uses the node), `d1 · d0 = 0` (relative
/// [`COMPLEX_TOLERANCE`]), and that the kernels leave the harmonic dimension the mesh's topology
/// gives (`2g` per closed component, `2g + b − 1` per component with `b` boundary loops).
pub struct MatrixComplex {
    parts: ComplexParts,
    sampler: Sampler,
    evaluation: Option<NodalEvaluation>,
}

impl MatrixComplex {
    /// Checks and wraps the matrices on a **closed** mesh (no fixed nodes), each node kind from
    /// its size or the sampling; `id` names the complex in basis files and messages. Errors say
    /// which matrix is wrong and how.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        id: &str,
        mesh: &SurfaceMesh,
        d0: CsMat<f64>,
        d1: CsMat<f64>,
        m0: Mass,
        m1: Mass,
        m2: Mass,
        sampling: MatrixSampling,
    ) -> Result<Self, DiscretizationError> {
        let matrices = ComplexMatrices { d0, d1, m0, m1, m2 };
        Self::with_node_kinds(id, mesh, matrices, &[None; 3], sampling)
    }

    /// [`MatrixComplex::new`] with the node kinds `stated` (a space with `None` gets the one
    /// kind of its size).
    pub fn with_node_kinds(
        id: &str,
        mesh: &SurfaceMesh,
        matrices: ComplexMatrices,
        stated: &StatedNodeKinds,
        sampling: MatrixSampling,
    ) -> Result<Self, DiscretizationError> {
        if !mesh.is_closed() {
            return Err(DiscretizationError::Inconsistent(
                "a complex from matrices without fixed nodes needs a closed mesh (the boundary \
                 condition of a mesh with boundary is not given by the matrices); use a catalog \
                 entry there"
                    .to_string(),
            ));
        }
        let fixed = FixedNodes::default();
        let condition = Default::default();
        Self::with_boundary(id, mesh, matrices, stated, &fixed, condition, sampling)
    }

    /// Checks and wraps the matrices on any mesh, with the node kinds `stated` (a space with
    /// `None` gets the one kind of its size): `fixed` are the nodes the boundary condition
    /// `condition` fixes to zero (none on a closed mesh; `condition` only matters on a mesh with
    /// boundary, where it is recorded in the topology). Errors say which matrix is wrong and
    /// how.
    pub fn with_boundary(
        id: &str,
        mesh: &SurfaceMesh,
        matrices: ComplexMatrices,
        stated: &StatedNodeKinds,
        fixed: &FixedNodes,
        condition: BoundaryCondition,
        sampling: MatrixSampling,
    ) -> Result<Self, DiscretizationError> {
        let ComplexMatrices { d0, d1, m0, m1, m2 } = matrices;
        let (n1, n0) = d0.shape();
        check_length("columns of d1 (n1, the rows of d0)", n1, d1.cols())?;
        let n2 = d1.rows();
        check_length("M0 (one entry per column of d0)", n0, m0.len())?;
        check_length("M1 (one entry per row of d0)", n1, m1.len())?;
        check_length("M2 (one entry per row of d1)", n2, m2.len())?;
        check_finite("d0", &d0)?;
        check_finite("d1", &d1)?;
        // The sampling's field kind settles a size two kinds share (E = 2F on closed quad
        // meshes); a sampling that does not fit the size is refused below, naming it.
        let sampled = sampling
            .field_kind()
            .filter(|&kind| kind_size(mesh, kind) == n1);
        let mut stated = *stated;
        stated[1] = stated[1].or(sampled);
        let spaces = matrix_node_spaces(mesh, &d0, &d1, &stated, fixed)?;
        check_complex(&d0, &d1)?;
        let topology = crate::mesh_topology(mesh, condition);
        let implied = implied_harmonic_dimension(&spaces);
        if implied != topology.harmonic_dimension as i64 {
            if let Some(orientation) = face_orientation_error(&d1, &spaces[2]) {
                return Err(DiscretizationError::Inconsistent(orientation));
            }
            return Err(DiscretizationError::Inconsistent(format!(
                "the matrices leave {implied} harmonic fields (free field nodes minus the ranks \
                 of d0 and d1, whose kernels are the constants found on each component), but the \
                 mesh's topology has {} (2g per closed component, 2g + b - 1 per component with \
                 b boundary loops){}",
                topology.harmonic_dimension,
                if mesh.is_closed() || fixed != &FixedNodes::default() {
                    ""
                } else {
                    "; on a mesh with boundary, give the nodes the boundary condition fixes"
                }
            )));
        }
        let sampler = sampler(mesh, sampling, &spaces[1])?;
        let evaluation = NodalEvaluation::new(mesh, spaces[0].kind, spaces[2].kind);
        Ok(Self {
            parts: ComplexParts::new(id, d0, d1, [m0, m1, m2], spaces, topology)?,
            sampler,
            evaluation,
        })
    }
}

/// For co-potentials on faces (2-forms): the error naming the face whose row of `d1` disagrees
/// with its neighbours when `d1ᵀ·1 ≠ 0` on edges shared by two faces — there the two faces'
/// counter-clockwise boundaries run along the edge in opposite directions, so their rows must
/// give it opposite signs, and a face row negated (or a face oriented against its neighbours)
/// takes the constants out of the kernel of `d1ᵀ`. `None` for other node kinds, or when every
/// shared edge sums to zero.
fn face_orientation_error(d1: &CsMat<f64>, co_potential_nodes: &NodeSpace) -> Option<String> {
    if co_potential_nodes.kind != NodeKind::Faces {
        return None;
    }
    let scale = max_abs(d1);
    let mut sums = vec![0.0; d1.cols()];
    let mut faces_of_edge = vec![0usize; d1.cols()];
    for (&value, (_, e)) in d1.iter() {
        sums[e] += value;
        faces_of_edge[e] += 1;
    }
    let disagreeing: Vec<bool> = (0..d1.cols())
        .map(|e| faces_of_edge[e] == 2 && sums[e].abs() > COMPLEX_TOLERANCE * scale)
        .collect();
    let count = disagreeing.iter().filter(|&&d| d).count();
    if count == 0 {
        return None;
    }
    let mut per_face = vec![(0usize, 0usize); d1.rows()];
    for (_, (t, e)) in d1.iter() {
        per_face[t].1 += 1;
        if disagreeing[e] {
            per_face[t].0 += 1;
        }
    }
    let (face, (bad, edges)) = per_face
        .iter()
        .enumerate()
        .max_by_key(|(_, (bad, _))| *bad)
        .map(|(t, &counts)| (t, counts))?;
    Some(format!(
        "d1ᵀ·1 ≠ 0 on {count} edges shared by two faces (their rows of d1 give each such edge          the same sign, but the counter-clockwise boundaries of two neighbouring faces run along          it in opposite directions): face {face} disagrees with its neighbours on {bad} of its          {edges} edges — is its row of d1 negated?"
    ))
}

/// Checks `d1 · d0 = 0` relative to `max |d1| · max |d0|`.
fn check_complex(d0: &CsMat<f64>, d1: &CsMat<f64>) -> Result<(), DiscretizationError> {
    let composed = product(d1, d0);
    let error = max_abs(&composed);
    let scale = max_abs(d1) * max_abs(d0);
    if error > COMPLEX_TOLERANCE * scale {
        return Err(DiscretizationError::Inconsistent(format!(
            "d1 · d0 is not zero: max |d1 d0| = {error:e}, above {COMPLEX_TOLERANCE:e} · \
             max |d1| · max |d0| = {:e}",
            COMPLEX_TOLERANCE * scale
        )));
    }
    Ok(())
}

/// The sampler `sampling` asks for, checked against the field nodes.
fn sampler(
    mesh: &SurfaceMesh,
    sampling: MatrixSampling,
    field_nodes: &NodeSpace,
) -> Result<Sampler, DiscretizationError> {
    Ok(match sampling {
        MatrixSampling::None => Sampler::None,
        MatrixSampling::FaceFrames => {
            require_kind("face-frames sampling", field_nodes, NodeKind::FaceFrames)?;
            Sampler::FaceFrames(FaceFields::new(triangles(mesh, sampling)?)?)
        }
        MatrixSampling::Whitney => {
            require_kind("Whitney sampling", field_nodes, NodeKind::Edges)?;
            let mesh = triangles(mesh, sampling)?;
            let geometry = FaceGeometry::new(mesh)?;
            Sampler::Whitney(WhitneySampling::new(
                mesh,
                &geometry,
                field_nodes.dirichlet.clone(),
            ))
        }
        MatrixSampling::PolygonSharp => {
            require_kind("polygon-sharp sampling", field_nodes, NodeKind::Edges)?;
            let operators: Vec<PolygonOperators> = (0..mesh.face_count())
                .map(|f| PolygonOperators::of(mesh, f))
                .collect();
            Sampler::PolygonSharp(PolygonSampling::new(
                mesh,
                &operators,
                field_nodes.dirichlet.clone(),
            ))
        }
    })
}

/// The triangle mesh a triangle sampling needs, or an error naming the sampling.
fn triangles(
    mesh: &SurfaceMesh,
    sampling: MatrixSampling,
) -> Result<&tvf_core::TriangleMesh, DiscretizationError> {
    mesh.as_triangles().ok_or_else(|| {
        DiscretizationError::Inconsistent(format!(
            "{} sampling needs a triangle mesh; on a polygon mesh use polygon-sharp (1-forms) or \
             none",
            sampling.name()
        ))
    })
}

fn check_finite(what: &'static str, a: &CsMat<f64>) -> Result<(), DiscretizationError> {
    match a.data().iter().position(|x| !x.is_finite()) {
        Some(index) => Err(DiscretizationError::NonFinite { what, index }),
        None => Ok(()),
    }
}

fn max_abs(a: &CsMat<f64>) -> f64 {
    a.data().iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn require_kind(what: &str, nodes: &NodeSpace, kind: NodeKind) -> Result<(), DiscretizationError> {
    if nodes.kind == kind {
        Ok(())
    } else {
        Err(DiscretizationError::Inconsistent(format!(
            "{what} needs fields on {}, but the field space has {} nodes ({})",
            kind.name(),
            nodes.len(),
            nodes.kind.name()
        )))
    }
}

impl HodgeComplex for MatrixComplex {
    fn parts(&self) -> &ComplexParts {
        &self.parts
    }

    fn sampling(&self) -> Option<&dyn FieldSampling> {
        match &self.sampler {
            Sampler::None => None,
            Sampler::FaceFrames(fields) => Some(fields),
            Sampler::Whitney(whitney) => Some(whitney),
            Sampler::PolygonSharp(sharp) => Some(sharp),
        }
    }
    fn rotation(&self) -> Option<&dyn FieldRotation> {
        match &self.sampler {
            Sampler::FaceFrames(fields) => Some(fields),
            _ => None,
        }
    }

    /// Evaluation by the node kinds ([`NodalEvaluation`]): vertex values linearly, edge values
    /// by Crouzeix–Raviart on triangles, face values constant; none for face frames.
    fn point_evaluation(&self) -> Option<&dyn PointEvaluation> {
        self.evaluation.as_ref().map(|e| e as &dyn PointEvaluation)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{catalog_entry, BoxedComplex};
    use tvf_core::discretization::HodgeOperators;
    use tvf_core::generate::{disk, icosphere, torus};

    /// `d0`, `d1` and the three masses of a complex.
    type Parts = (CsMat<f64>, CsMat<f64>, Mass, Mass, Mass);

    /// The complex of built-in catalog entry `id` on `mesh`, default boundary condition.
    fn catalog_complex(id: &str, mesh: &SurfaceMesh) -> BoxedComplex {
        catalog_entry(id).unwrap().build(mesh).unwrap()
    }

    fn parts(c: &dyn HodgeComplex) -> Parts {
        (
            c.d0().clone(),
            c.d1().clone(),
            c.m0().clone(),
            c.m1().clone(),
            c.m2().clone(),
        )
    }

    /// [`MatrixComplex::new`] of `parts` on the closed `mesh`.
    fn closed_copy(
        mesh: &SurfaceMesh,
        (d0, d1, m0, m1, m2): Parts,
        sampling: MatrixSampling,
    ) -> Result<MatrixComplex, DiscretizationError> {
        MatrixComplex::new("copy", mesh, d0, d1, m0, m1, m2, sampling)
    }

    /// [`MatrixComplex::with_boundary`] of `parts` on `mesh` with `fixed` nodes, without sampling.
    fn copy_with_fixed(
        mesh: &SurfaceMesh,
        (d0, d1, m0, m1, m2): Parts,
        fixed: &FixedNodes,
        condition: BoundaryCondition,
    ) -> Result<MatrixComplex, DiscretizationError> {
        let matrices = ComplexMatrices { d0, d1, m0, m1, m2 };
        MatrixComplex::with_boundary(
            "copy",
            mesh,
            matrices,
            &[None; 3],
            fixed,
            condition,
            MatrixSampling::None,
        )
    }

    /// The message of a refused complex.
    fn refusal(result: Result<MatrixComplex, DiscretizationError>) -> String {
        result.err().expect("the matrices are refused").to_string()
    }

    fn diagonal(mass: &Mass) -> Vec<f64> {
        mass.diagonal_values().unwrap().to_vec()
    }

    /// A `d1` with one face row negated still has `d1 d0 = 0` but leaves the constants of the
    /// 2-forms out of its kernel: the refusal names `d1ᵀ·1 ≠ 0` and the face, not only a wrong
    /// count of harmonic fields.
    #[test]
    fn a_negated_face_row_of_d1_is_named() {
        let mesh = SurfaceMesh::from(icosphere(1));
        let built = catalog_complex("dec-barycentric", &mesh);
        let (d0, d1, m0, m1, m2) = parts(built.as_ref());
        let mut d1 = d1.to_csr();
        let row = {
            let indptr = d1.indptr();
            let starts = indptr.raw_storage();
            starts[7]..starts[8]
        };
        for value in &mut d1.data_mut()[row] {
            *value = -*value;
        }
        let message = refusal(closed_copy(
            &mesh,
            (d0, d1, m0, m1, m2),
            MatrixSampling::Whitney,
        ));
        assert!(
            message.contains("d1ᵀ·1 ≠ 0 on 3 edges") && message.contains("face 7 disagrees"),
            "{message}"
        );
    }

    #[test]
    fn rebuilds_a_catalog_complex_with_its_operators() {
        let mesh = SurfaceMesh::from(torus(1.0, 0.4, 12, 6).unwrap());
        let built = catalog_complex("conforming-barycentric", &mesh);
        let copy = closed_copy(&mesh, parts(built.as_ref()), MatrixSampling::FaceFrames).unwrap();
        assert_eq!(copy.potential_nodes().kind, NodeKind::Vertices);
        assert_eq!(copy.co_potential_nodes().kind, NodeKind::Edges);
        assert_eq!(copy.topology().harmonic_dimension, 2);
        let (copied, original) = (
            copy.dirichlet_energy().as_sparse().unwrap(),
            built.dirichlet_energy().as_sparse().unwrap(),
        );
        let difference = copied - original;
        assert!(max_abs(&difference) <= 1e-14 * max_abs(original));
        assert!(copy.rotation().is_some());
    }

    /// Every catalog entry, rebuilt from its matrices and fixed nodes on a closed and an open
    /// mesh under both boundary conditions, has the catalog's matrix hash: the computed kernels
    /// and the fixed nodes are the entry's own.
    #[test]
    fn rebuilds_every_entry_with_its_fixed_nodes_and_kernels() {
        use crate::builtin_catalog;
        let meshes = [SurfaceMesh::from(icosphere(1)), disk(3).into()];
        for mesh in &meshes {
            for entry in builtin_catalog() {
                for condition in BoundaryCondition::ALL {
                    let Ok(built) = entry.build_with(mesh, condition) else {
                        continue;
                    };
                    let fixed = FixedNodes::of([
                        built.potential_nodes(),
                        built.field_nodes(),
                        built.co_potential_nodes(),
                    ]);
                    let copy = copy_with_fixed(mesh, parts(built.as_ref()), &fixed, condition)
                        .unwrap_or_else(|e| panic!("{} {condition:?}: {e}", entry.id()));
                    assert_eq!(
                        copy.matrix_hash(),
                        built.matrix_hash(),
                        "{} {condition:?} on {} faces",
                        entry.id(),
                        mesh.face_count()
                    );
                }
            }
        }
    }

    #[test]
    fn an_open_mesh_needs_its_fixed_nodes() {
        let mesh = SurfaceMesh::from(disk(3));
        let built = catalog_complex("conforming-barycentric", &mesh);
        let refused_with = |fixed: &FixedNodes| {
            refusal(copy_with_fixed(
                &mesh,
                parts(built.as_ref()),
                fixed,
                BoundaryCondition::Tangential,
            ))
        };
        let message = refused_with(&FixedNodes::default());
        assert!(
            message.contains("give the nodes the boundary condition fixes"),
            "{message}"
        );
        let message = refused_with(&FixedNodes {
            potentials: vec![0],
            ..FixedNodes::default()
        });
        assert!(
            message.contains("fixed potential node 0 has a nonzero column of d0"),
            "{message}"
        );
    }

    /// On a quad torus `V = F` and `E = 2F`: the sizes alone cannot tell vertices from faces,
    /// so a complex without stated node kinds is refused naming the ambiguity, and with them it
    /// is the catalog's polygon-dec (same matrices, node kinds and harmonic dimension).
    #[test]
    fn a_size_two_kinds_share_needs_the_stated_kind() {
        let mesh = SurfaceMesh::from(tvf_core::generate::quad_torus(1.0, 0.4, 8, 8).unwrap());
        assert_eq!(mesh.vertex_count(), mesh.face_count());
        let built = catalog_complex("polygon-dec", &mesh);
        let message = refusal(closed_copy(
            &mesh,
            parts(built.as_ref()),
            MatrixSampling::PolygonSharp,
        ));
        assert!(
            message.contains("potential space (columns of d0) has 64 nodes, which is ambiguous")
                && message.contains("64 vertices and 64 faces"),
            "{message}"
        );
        let (d0, d1, m0, m1, m2) = parts(built.as_ref());
        let matrices = ComplexMatrices { d0, d1, m0, m1, m2 };
        let stated = [Some(NodeKind::Vertices), None, Some(NodeKind::Faces)];
        let copy = MatrixComplex::with_node_kinds(
            "copy",
            &mesh,
            matrices,
            &stated,
            MatrixSampling::PolygonSharp,
        )
        .unwrap();
        assert_eq!(copy.potential_nodes().kind, NodeKind::Vertices);
        assert_eq!(copy.field_nodes().kind, NodeKind::Edges);
        assert_eq!(copy.co_potential_nodes().kind, NodeKind::Faces);
        assert_eq!(
            copy.co_potential_nodes().positions,
            built.co_potential_nodes().positions
        );
        assert_eq!(copy.topology().harmonic_dimension, 2);
        assert_eq!(copy.matrix_hash(), built.matrix_hash());
        let wrong = [Some(NodeKind::Edges), None, None];
        let (d0, d1, m0, m1, m2) = parts(built.as_ref());
        let matrices = ComplexMatrices { d0, d1, m0, m1, m2 };
        let message =
            MatrixComplex::with_node_kinds("copy", &mesh, matrices, &wrong, MatrixSampling::None)
                .err()
                .unwrap()
                .to_string();
        assert!(
            message
                .contains("has 64 nodes, but its nodes are stated to be edges: the mesh has 128"),
            "{message}"
        );
    }

    #[test]
    fn whitney_sampling_needs_edge_fields() {
        let mesh = SurfaceMesh::from(icosphere(1));
        let dec = catalog_complex("dec-circumcentric", &mesh);
        let ok = closed_copy(&mesh, parts(dec.as_ref()), MatrixSampling::Whitney);
        assert!(ok.unwrap().sampling().is_some());
        let message = refusal(closed_copy(
            &mesh,
            parts(dec.as_ref()),
            MatrixSampling::FaceFrames,
        ));
        assert!(
            message.contains("face-frames sampling needs fields on face-frames"),
            "{message}"
        );
    }

    #[test]
    fn refuses_broken_matrices_naming_them() {
        let mesh = SurfaceMesh::from(icosphere(1));
        let built = catalog_complex("conforming-barycentric", &mesh);
        let (d0, d1, m0, m1, m2) = parts(built.as_ref());
        let build = |d0: CsMat<f64>, m1: Mass| {
            let parts = (d0, d1.clone(), m0.clone(), m1, m2.clone());
            refusal(closed_copy(&mesh, parts, MatrixSampling::None))
        };
        let mut broken = d0.clone();
        broken.data_mut()[3] += 0.5;
        assert!(build(broken, m1.clone()).contains("d1 · d0 is not zero"));
        let mut nan = d0.clone();
        nan.data_mut()[0] = f64::NAN;
        assert!(build(nan, m1.clone()).contains("d0 contains a non-finite value"));
        let mut zero = diagonal(&m1);
        zero[5] = 0.0;
        let zero = Mass::diagonal("M1", zero).unwrap();
        assert!(build(d0.clone(), zero).contains("M1 must be positive"));
        let mut negative = diagonal(&m1);
        negative[5] = -1.0;
        assert!(Mass::diagonal("M1", negative)
            .unwrap_err()
            .to_string()
            .contains("M1 must be positive"));
        let short = Mass::diagonal("M1", diagonal(&m1)[1..].to_vec()).unwrap();
        assert!(build(d0, short).contains("M1 (one entry per row of d0)"));
    }
}
