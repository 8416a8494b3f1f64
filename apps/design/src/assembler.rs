//! [`ConstraintAssembler`]: turns [`Constraint`]s into rows `C̃` over the field coefficients, for
//! any [`HodgeComplex`].

use crate::constraint::{
    CompiledConstraint, Constraint, Location, OperatorFamily, RowOrigin, SparseRow, Target,
};
use crate::error::ConstraintError;
use std::collections::{BTreeMap, HashSet};
use tvf_core::discretization::{
    HodgeComplex, HodgeOperators, LinearOperator, NodeKind, NodeSpace, PointEvaluation,
};
use tvf_core::mesh::Mesh;
use tvf_core::SurfacePoint;

/// Tolerance on `|Σ b − 1|` for barycentric coordinates.
const BARYCENTRIC_TOLERANCE: f64 = 1e-9;

/// Which space of the complex a scalar operator maps into.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Space {
    Potentials,
    CoPotentials,
}

/// Builds constraint rows for one mesh and one discretization.
///
/// Rows (all **pointwise**, over the `n1` field coefficients; each with its [`RowOrigin`]):
/// - vector at a point of face `t` (the centroid without `barycentric`): the two rows of the
///   sampled vector in the face frame ([`tvf_core::discretization::FieldSampling::sample_frame_weights`]; face fields: the
///   identity on `x[2t], x[2t+1]`); the 3D value is projected onto the face plane
///   (`(v·e1, v·e2)`).
/// - divergence at a node: the node's row of `potential_divergence` (`−M0⁻¹ d0ᵀ M1`), or of
///   `other_divergence` for [`OperatorFamily::Other`].
/// - curl at a node: the node's row of `co_potential_curl` (`M2 d1`), or of `other_curl` for
///   [`OperatorFamily::Other`].
/// - divergence / curl at a point of a face: the nodal rows mixed with the space's interpolation
///   weights at the point ([`PointEvaluation`]).
///
/// Where the operator is composed (an inverse of a non-diagonal mass inside) the row is dense: it
/// is computed as one transposed application of the operator to the interpolation weights (a
/// mass solve), never from a dense matrix.
///
/// `vertex` / `edge` locations address nodes of a space whose nodes are vertices / edges (read
/// off [`NodeSpace::kind`]); a key that does not fit the requested family's space is rejected with
/// [`ConstraintError::NodeKindMismatch`].
pub struct ConstraintAssembler<'a, H: HodgeComplex + ?Sized> {
    complex: &'a H,
    vertex_count: usize,
    edge_count: usize,
    /// The number of corners of every face (what `barycentric` must have).
    face_sizes: Vec<usize>,
}

impl<'a, H: HodgeComplex + ?Sized> ConstraintAssembler<'a, H> {
    /// An assembler for `complex` (built on `mesh`); operators come from the complex's cache.
    pub fn new<M: Mesh + ?Sized>(complex: &'a H, mesh: &M) -> Self {
        Self {
            complex,
            vertex_count: mesh.vertex_count(),
            edge_count: mesh.edge_count(),
            face_sizes: (0..mesh.face_count())
                .map(|f| mesh.face_corners().corners(f).len())
                .collect(),
        }
    }

    /// Number of faces `F`.
    pub fn face_count(&self) -> usize {
        self.face_sizes.len()
    }

    /// Checks `constraint` against the mesh (indices, barycentric coordinates, finiteness) and
    /// returns its rows and values.
    pub fn compile(&self, constraint: &Constraint) -> Result<CompiledConstraint, ConstraintError> {
        let id = &constraint.id;
        if !(constraint.weight.is_finite() && constraint.weight > 0.0) {
            return Err(ConstraintError::NotFinite {
                id: id.clone(),
                what: "weight",
                extra: " and positive",
            });
        }
        if !constraint.target.is_finite() {
            return Err(ConstraintError::NotFinite {
                id: id.clone(),
                what: "value",
                extra: "",
            });
        }
        self.check_location(id, &constraint.location)?;
        let (rows, values, origins) = match constraint.target {
            Target::Vector(v) => {
                let (rows, values) = self.vector_rows(id, &constraint.location, v)?;
                (rows, values, vec![RowOrigin::Field; 2])
            }
            Target::Divergence(s) => {
                let space = match constraint.family {
                    OperatorFamily::Decomposition => Space::Potentials,
                    OperatorFamily::Other => Space::CoPotentials,
                };
                let (row, origin) = self.scalar_row(constraint, "divergence", space)?;
                (vec![row], vec![s], vec![origin])
            }
            Target::Curl(s) => {
                let space = match constraint.family {
                    OperatorFamily::Decomposition => Space::CoPotentials,
                    OperatorFamily::Other => Space::Potentials,
                };
                let (row, origin) = self.scalar_row(constraint, "curl", space)?;
                (vec![row], vec![s], vec![origin])
            }
        };
        if rows.iter().any(|row| row.iter().all(|&(_, a)| a == 0.0)) {
            return Err(ConstraintError::EmptyRow { id: id.clone() });
        }
        Ok(CompiledConstraint {
            id: id.clone(),
            rows,
            values,
            weight: constraint.weight,
            origins,
        })
    }

    /// Compiles a whole list, rejecting duplicate ids.
    pub fn compile_all(
        &self,
        constraints: &[Constraint],
    ) -> Result<Vec<CompiledConstraint>, ConstraintError> {
        let mut seen = HashSet::new();
        constraints
            .iter()
            .map(|c| {
                if !seen.insert(c.id.as_str()) {
                    return Err(ConstraintError::DuplicateId { id: c.id.clone() });
                }
                self.compile(c)
            })
            .collect()
    }

    fn check_location(&self, id: &str, location: &Location) -> Result<(), ConstraintError> {
        let range = |what, index: usize, count: usize| {
            if index < count {
                Ok(())
            } else {
                Err(ConstraintError::OutOfRange {
                    id: id.to_string(),
                    what,
                    index: i64::try_from(index).unwrap_or(i64::MAX),
                    count,
                })
            }
        };
        match *location {
            Location::Face {
                face,
                ref barycentric,
            } => {
                range("face", face, self.face_count())?;
                if let Some(b) = barycentric {
                    check_barycentric(id, b)?;
                    let corners = self.face_sizes[face];
                    if b.len() != corners {
                        return Err(ConstraintError::WrongCornerCount {
                            id: id.to_string(),
                            face,
                            corners,
                            weights: b.len(),
                        });
                    }
                }
                Ok(())
            }
            Location::Vertex(v) => range("vertex", v, self.vertex_count),
            Location::Edge(e) => range("edge", e, self.edge_count),
        }
    }

    fn vector_rows(
        &self,
        id: &str,
        location: &Location,
        value: [f64; 3],
    ) -> Result<(Vec<SparseRow>, Vec<f64>), ConstraintError> {
        let &Location::Face {
            face,
            ref barycentric,
        } = location
        else {
            return Err(ConstraintError::BadLocation {
                id: id.to_string(),
                problem:
                    "a vector constraint needs a \"face\" (the field is sampled at a point of it)"
                        .into(),
            });
        };
        let sampling = self
            .complex
            .require_sampling()
            .map_err(|e| unsupported(id, e))?;
        let point = match barycentric {
            Some(weights) => SurfacePoint {
                face,
                weights: weights.clone(),
            },
            None => sampling.centroid(face),
        };
        let weights = sampling.sample_frame_weights(&point);
        let [e1, e2] = sampling.frame(face);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let row = |k: usize| -> SparseRow {
            let mut row = BTreeMap::new();
            for &(i, w) in &weights {
                *row.entry(i).or_insert(0.0) += w[k];
            }
            row.into_iter().filter(|&(_, a)| a != 0.0).collect()
        };
        Ok((vec![row(0), row(1)], vec![dot(value, e1), dot(value, e2)]))
    }

    /// The pointwise operator of `kind` in `space`, and that space's nodes.
    fn operator(
        &self,
        constraint: &Constraint,
        kind: &'static str,
        space: Space,
    ) -> Result<(&'a LinearOperator, &'a NodeSpace), ConstraintError> {
        let complex = self.complex;
        let other = |matrix: Option<&'a LinearOperator>| {
            matrix.ok_or_else(|| ConstraintError::Unsupported {
                id: constraint.id.clone(),
                detail: format!(
                    "the discretization '{}' has no other family of divergence and curl; drop \"family\": \"other\"",
                    complex.id()
                ),
            })
        };
        Ok(match (kind, space) {
            ("divergence", Space::Potentials) => {
                (complex.potential_divergence(), complex.potential_nodes())
            }
            ("divergence", _) => (
                other(complex.other_divergence())?,
                complex.co_potential_nodes(),
            ),
            (_, Space::CoPotentials) => (complex.co_potential_curl(), complex.co_potential_nodes()),
            _ => (other(complex.other_curl())?, complex.potential_nodes()),
        })
    }

    /// The row of a divergence or curl constraint and what it is made of.
    fn scalar_row(
        &self,
        constraint: &Constraint,
        kind: &'static str,
        space: Space,
    ) -> Result<(SparseRow, RowOrigin), ConstraintError> {
        let (matrix, nodes) = self.operator(constraint, kind, space)?;
        let weights: Vec<(usize, f64)> = match constraint.location {
            Location::Face {
                face,
                ref barycentric,
            } => {
                let evaluation: &dyn PointEvaluation = self
                    .complex
                    .require_point_evaluation()
                    .map_err(|e| unsupported(&constraint.id, e))?;
                let point = match (barycentric, self.complex.sampling()) {
                    (Some(weights), _) => SurfacePoint {
                        face,
                        weights: weights.clone(),
                    },
                    (None, Some(sampling)) => sampling.centroid(face),
                    (None, None) => SurfacePoint::centroid(face, self.face_sizes[face]),
                };
                match space {
                    Space::Potentials => evaluation.potential_weights(&point),
                    Space::CoPotentials => evaluation.co_potential_weights(&point),
                }
            }
            Location::Vertex(node) => {
                self.check_node_kind(constraint, kind, space, nodes.kind, NodeKind::Vertices)?;
                self.check_not_dirichlet(constraint, kind, nodes, node)?;
                vec![(node, 1.0)]
            }
            Location::Edge(node) => {
                self.check_node_kind(constraint, kind, space, nodes.kind, NodeKind::Edges)?;
                self.check_not_dirichlet(constraint, kind, nodes, node)?;
                vec![(node, 1.0)]
            }
        };
        let origin = match (constraint.family, space) {
            (OperatorFamily::Decomposition, Space::Potentials) => {
                // potential_divergence = −M0⁻¹ d0ᵀ M1.
                RowOrigin::Potential(nonzero(weights.iter().map(|&(i, w)| (i, -w))))
            }
            (OperatorFamily::Decomposition, Space::CoPotentials) => {
                // co_potential_curl = M2 d1.
                RowOrigin::CoPotential(nonzero(weights.iter().copied()))
            }
            (OperatorFamily::Other, _) if matrix.is_sparse() => RowOrigin::Field,
            (OperatorFamily::Other, _) => RowOrigin::Composed,
        };
        let mut row = BTreeMap::new();
        match matrix.as_sparse() {
            Some(matrix) => {
                for (node, w) in weights {
                    if w == 0.0 {
                        continue;
                    }
                    if let Some(lane) = matrix.outer_view(node) {
                        for (col, &a) in lane.iter() {
                            *row.entry(col).or_insert(0.0) += w * a;
                        }
                    }
                }
            }
            None => {
                // A composed operator (an inverse mass inside): its rows are dense; the weighted
                // combination of rows is one transposed application.
                let mut combination = vec![0.0; matrix.rows()];
                for (node, w) in weights {
                    combination[node] += w;
                }
                for (col, a) in matrix.apply_transpose(&combination).into_iter().enumerate() {
                    row.insert(col, a);
                }
            }
        }
        Ok((row.into_iter().filter(|&(_, a)| a != 0.0).collect(), origin))
    }

    /// A divergence or curl at a node the boundary condition fixes (a Dirichlet node, whose row of
    /// the operator is zero) cannot be prescribed.
    fn check_not_dirichlet(
        &self,
        constraint: &Constraint,
        kind: &'static str,
        nodes: &NodeSpace,
        node: usize,
    ) -> Result<(), ConstraintError> {
        if !nodes.dirichlet.get(node).copied().unwrap_or(false) {
            return Ok(());
        }
        Err(ConstraintError::Unsupported {
            id: constraint.id.clone(),
            detail: format!(
                "{} {node} lies on the boundary, where the boundary condition '{}' of '{}' fixes the values: its {kind} is zero and cannot be prescribed (use an interior node, or the other --boundary)",
                nodes.kind.name(),
                self.complex.topology().boundary_condition.name(),
                self.complex.id()
            ),
        })
    }

    /// Fails unless the constraint's node kind `given` is that of its operator's space
    /// (`nodes`, the nodes of `space`); the error says which key to use instead, and suggests the
    /// other family only where it exists (a complex with a rotation `J`, or back to the
    /// decomposition) and lives on the nodes given.
    fn check_node_kind(
        &self,
        constraint: &Constraint,
        kind: &'static str,
        space: Space,
        nodes: NodeKind,
        given: NodeKind,
    ) -> Result<(), ConstraintError> {
        if nodes == given {
            return Ok(());
        }
        let key = |k: NodeKind| match k {
            NodeKind::Vertices => "vertex",
            NodeKind::Edges => "edge",
            NodeKind::Faces | NodeKind::FaceFrames => "face",
        };
        let (other_family, available) = match constraint.family {
            OperatorFamily::Decomposition => {
                (OperatorFamily::Other, self.complex.rotation().is_some())
            }
            OperatorFamily::Other => (OperatorFamily::Decomposition, true),
        };
        let other_nodes = match space {
            Space::Potentials => self.complex.co_potential_nodes().kind,
            Space::CoPotentials => self.complex.potential_nodes().kind,
        };
        let alternative = if available && other_nodes == given {
            format!(" (or \"family\": \"{}\")", other_family.name())
        } else {
            String::new()
        };
        Err(ConstraintError::NodeKindMismatch {
            id: constraint.id.clone(),
            detail: format!(
                "the {} {kind} of '{}' lives on {}, not on the {} given; use \"{}\"{alternative}",
                constraint.family.name(),
                self.complex.id(),
                nodes.name(),
                key(given),
                key(nodes),
            ),
        })
    }
}

/// The weights summed per node, without zeros, ascending by node.
fn nonzero(weights: impl Iterator<Item = (usize, f64)>) -> SparseRow {
    let mut summed = BTreeMap::new();
    for (node, w) in weights {
        *summed.entry(node).or_insert(0.0) += w;
    }
    summed.into_iter().filter(|&(_, w)| w != 0.0).collect()
}

fn unsupported(id: &str, error: impl std::fmt::Display) -> ConstraintError {
    ConstraintError::Unsupported {
        id: id.to_string(),
        detail: error.to_string(),
    }
}

/// Checks that `b` has at least three entries, finite, non-negative and summing to 1 (to 1e-9).
pub(crate) fn check_barycentric(id: &str, b: &[f64]) -> Result<(), ConstraintError> {
    let ok = b.len() >= 3
        && b.iter().all(|x| x.is_finite() && *x >= 0.0)
        && (b.iter().sum::<f64>() - 1.0).abs() <= BARYCENTRIC_TOLERANCE;
    if ok {
        Ok(())
    } else {
        Err(ConstraintError::BadBarycentric {
            id: id.to_string(),
            values: b.to_vec(),
        })
    }
}
