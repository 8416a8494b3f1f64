//! [`MatrixComplex`]: a complex made of five matrices someone else assembled (a researcher's own
//! discretization, e.g. from Python), checked before anything downstream sees it.

use crate::face_fields::FaceFields;
use crate::face_geometry::FaceGeometry;
use crate::whitney_sampling::WhitneySampling;
use sprs::CsMat;
use tvf_core::discretization::check_length;
use tvf_core::discretization::sparse::product;
use tvf_core::discretization::{
    ComplexParts, DiscretizationError, FieldRotation, FieldSampling, HodgeComplex, Mass, NodeKind,
    NodeSpace,
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
    /// Whitney interpolation: `n1 = E`.
    Whitney,
}

impl MatrixSampling {
    /// The sampling named `name`: `none`, `face-frames` or `whitney`.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "none" => Some(Self::None),
            "face-frames" => Some(Self::FaceFrames),
            "whitney" => Some(Self::Whitney),
            _ => None,
        }
    }
}

/// What samples the fields of a [`MatrixComplex`].
enum Sampler {
    None,
    FaceFrames(FaceFields),
    Whitney(WhitneySampling),
}

/// A [`HodgeComplex`] from the five matrices `d0` (`n1 × n0`), `d1` (`n2 × n1`) and the masses
/// `M0`, `M1`, `M2` (each a [`Mass`]: a diagonal, a sparse matrix, or for `M2` also the sparse
/// inverse), on a **closed** mesh. The node kind of each space follows from its size
/// (`V` vertices, `E` edges, `F` faces, `2F` face frames; checked in that order), node positions
/// and components from the mesh. [`MatrixComplex::new`] checks everything the seam promises:
/// shapes, finite entries, masses symmetric positive definite on the nodes some face uses (a
/// diagonal may be zero where no face uses the node), and `d1 · d0 = 0` (relative
/// [`COMPLEX_TOLERANCE`]).
pub struct MatrixComplex {
    parts: ComplexParts,
    sampler: Sampler,
}

impl MatrixComplex {
    /// Checks and wraps the matrices; `id` names the complex in basis files and messages. Errors
    /// say which matrix is wrong and how.
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
        if !mesh.is_closed() {
            return Err(DiscretizationError::Inconsistent(
                "a complex from matrices needs a closed mesh (the boundary condition of a mesh \
                 with boundary is not given by the matrices); use a catalog entry there"
                    .to_string(),
            ));
        }
        let (n1, n0) = d0.shape();
        check_length("columns of d1 (n1, the rows of d0)", n1, d1.cols())?;
        let n2 = d1.rows();
        check_length("M0 (one entry per column of d0)", n0, m0.len())?;
        check_length("M1 (one entry per row of d0)", n1, m1.len())?;
        check_length("M2 (one entry per row of d1)", n2, m2.len())?;
        check_finite("d0", &d0)?;
        check_finite("d1", &d1)?;
        let potential_nodes = node_space(mesh, n0, "potential space (columns of d0)")?;
        let field_nodes = node_space(mesh, n1, "field space (rows of d0)")?;
        let co_potential_nodes = node_space(mesh, n2, "co-potential space (rows of d1)")?;
        let composed = product(&d1, &d0);
        let error = max_abs(&composed);
        let scale = max_abs(&d1) * max_abs(&d0);
        if error > COMPLEX_TOLERANCE * scale {
            return Err(DiscretizationError::Inconsistent(format!(
                "d1 · d0 is not zero: max |d1 d0| = {error:e}, above {COMPLEX_TOLERANCE:e} · \
                 max |d1| · max |d0| = {:e}",
                COMPLEX_TOLERANCE * scale
            )));
        }
        let sampler = match sampling {
            MatrixSampling::None => Sampler::None,
            MatrixSampling::FaceFrames => {
                require_kind("face-frames sampling", &field_nodes, NodeKind::FaceFrames)?;
                Sampler::FaceFrames(FaceFields::new(mesh)?)
            }
            MatrixSampling::Whitney => {
                require_kind("Whitney sampling", &field_nodes, NodeKind::Edges)?;
                let geometry = FaceGeometry::new(mesh)?;
                Sampler::Whitney(WhitneySampling::new(
                    mesh,
                    &geometry,
                    field_nodes.dirichlet.clone(),
                ))
            }
        };
        Ok(Self {
            parts: ComplexParts::new(
                id,
                d0,
                d1,
                [m0, m1, m2],
                [potential_nodes, field_nodes, co_potential_nodes],
                crate::mesh_topology(mesh, Default::default()),
            )?,
            sampler,
        })
    }
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

/// The node space of `n` nodes on `mesh`: vertices, edges, faces or face frames by size.
fn node_space(mesh: &SurfaceMesh, n: usize, what: &str) -> Result<NodeSpace, DiscretizationError> {
    let positions = mesh.positions();
    let centroid = |face: &[usize; 3]| {
        let p = face.map(|v| positions[v]);
        [0, 1, 2].map(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0)
    };
    let (kind, positions, components) = if n == mesh.vertex_count() {
        (
            NodeKind::Vertices,
            positions.to_vec(),
            mesh.vertex_components(),
        )
    } else if n == mesh.edge_count() {
        let midpoints = mesh
            .edges()
            .iter()
            .map(|&[a, b]| [0, 1, 2].map(|k| 0.5 * (positions[a][k] + positions[b][k])))
            .collect();
        (NodeKind::Edges, midpoints, mesh.edge_components())
    } else if n == mesh.face_count() {
        let centroids = mesh.faces().iter().map(centroid).collect();
        (NodeKind::Faces, centroids, mesh.face_components().to_vec())
    } else if n == 2 * mesh.face_count() {
        let centroids = mesh.faces().iter().flat_map(|f| [centroid(f); 2]).collect();
        let components = mesh
            .face_components()
            .iter()
            .flat_map(|&c| [c; 2])
            .collect();
        (NodeKind::FaceFrames, centroids, components)
    } else {
        return Err(DiscretizationError::Inconsistent(format!(
            "the {what} has {n} nodes: not the mesh's {} vertices, {} edges, {} faces or {} \
             face-frame coefficients",
            mesh.vertex_count(),
            mesh.edge_count(),
            mesh.face_count(),
            2 * mesh.face_count()
        )));
    };
    Ok(NodeSpace::with_constant_kernel(
        kind,
        positions,
        components,
        mesh.component_count(),
    ))
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
        }
    }
    fn rotation(&self) -> Option<&dyn FieldRotation> {
        match &self.sampler {
            Sampler::FaceFrames(fields) => Some(fields),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog_entry;
    use tvf_core::discretization::HodgeOperators;
    use tvf_core::generate::{icosphere, torus};

    /// `d0`, `d1` and the three masses of a complex.
    type Parts = (CsMat<f64>, CsMat<f64>, Mass, Mass, Mass);

    fn parts(c: &dyn HodgeComplex) -> Parts {
        (
            c.d0().clone(),
            c.d1().clone(),
            c.m0().clone(),
            c.m1().clone(),
            c.m2().clone(),
        )
    }

    fn diagonal(mass: &Mass) -> Vec<f64> {
        mass.diagonal_values().unwrap().to_vec()
    }

    #[test]
    fn rebuilds_a_catalog_complex_with_its_operators() {
        let mesh = torus(1.0, 0.4, 12, 6).unwrap();
        let built = catalog_entry("conforming-barycentric")
            .unwrap()
            .build(&mesh)
            .unwrap();
        let (d0, d1, m0, m1, m2) = parts(built.as_ref());
        let copy = MatrixComplex::new(
            "copy",
            &mesh,
            d0,
            d1,
            m0,
            m1,
            m2,
            MatrixSampling::FaceFrames,
        )
        .unwrap();
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

    #[test]
    fn whitney_sampling_needs_edge_fields() {
        let mesh = icosphere(1);
        let dec = catalog_entry("dec-circumcentric")
            .unwrap()
            .build(&mesh)
            .unwrap();
        let (d0, d1, m0, m1, m2) = parts(dec.as_ref());
        let ok = MatrixComplex::new(
            "dec",
            &mesh,
            d0.clone(),
            d1.clone(),
            m0.clone(),
            m1.clone(),
            m2.clone(),
            MatrixSampling::Whitney,
        );
        assert!(ok.unwrap().sampling().is_some());
        let wrong =
            MatrixComplex::new("dec", &mesh, d0, d1, m0, m1, m2, MatrixSampling::FaceFrames);
        let message = wrong.err().unwrap().to_string();
        assert!(
            message.contains("face-frames sampling needs fields on face-frames"),
            "{message}"
        );
    }

    #[test]
    fn refuses_broken_matrices_naming_them() {
        let mesh = icosphere(1);
        let built = catalog_entry("conforming-barycentric")
            .unwrap()
            .build(&mesh)
            .unwrap();
        let (d0, d1, m0, m1, m2) = parts(built.as_ref());
        let build = |d0: CsMat<f64>, m1: Mass| {
            MatrixComplex::new(
                "x",
                &mesh,
                d0,
                d1.clone(),
                m0.clone(),
                m1,
                m2.clone(),
                MatrixSampling::None,
            )
            .err()
            .unwrap()
            .to_string()
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
