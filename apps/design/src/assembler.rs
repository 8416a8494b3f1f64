//! [`ConstraintAssembler`]: turns [`Constraint`]s into rows `C̃` over the field coefficients, for
//! any [`HodgeComplex`].

use crate::constraint::{
    CompiledConstraint, Constraint, Location, OperatorFamily, SparseRow, Target,
};
use crate::error::ConstraintError;
use sprs::CsMat;
use std::collections::{BTreeMap, HashSet};
use tvf_core::discretization::{FieldSpace, FunctionSpace, HodgeComplex, HodgeOperators};
use tvf_core::SurfaceMesh;

/// Tolerance on `|Σ b − 1|` for barycentric coordinates.
const BARYCENTRIC_TOLERANCE: f64 = 1e-9;

/// Which function space a scalar operator maps into.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Space {
    Potentials,
    CoPotentials,
}

/// Builds constraint rows for one mesh and one discretization.
///
/// Rows (all **pointwise**, `2F` columns):
/// - vector in face `t`: the two rows `e_{2t}`, `e_{2t+1}` (identity in the face frame); the 3D
///   value is projected onto the face plane (`(v·e1, v·e2)`).
/// - divergence at a node: the node's row of `potential_divergence` (`−M0⁻¹ d0ᵀ M1`; conforming
///   `div_h`, nodes = vertices), or of `co_potential_divergence` for [`OperatorFamily::Other`].
/// - curl at a node: the node's row of `co_potential_curl` (`M2 d1`; conforming `curl*_h`, nodes =
///   edges), or of `potential_curl` for [`OperatorFamily::Other`].
/// - divergence / curl at a point of a face: the nodal rows mixed with the interpolation weights of
///   that space at the point ([`FunctionSpace::interpolation_weights`]).
///
/// `vertex` / `edge` locations address nodes of the P1 / Crouzeix–Raviart space; which space an
/// operator lives in is read off its dimension (`V` or `E` of `mesh`), so a key that does not fit
/// the requested family is rejected with [`ConstraintError::NodeKindMismatch`].
pub struct ConstraintAssembler<'a, H: HodgeComplex> {
    complex: &'a H,
    vertex_count: usize,
    edge_count: usize,
    face_count: usize,
    potential_divergence: CsMat<f64>,
    co_potential_curl: CsMat<f64>,
    co_potential_divergence: CsMat<f64>,
    potential_curl: CsMat<f64>,
}

impl<'a, H: HodgeComplex> ConstraintAssembler<'a, H> {
    /// Precomputes the four pointwise divergence / curl operators of `complex` (built on `mesh`).
    pub fn new(complex: &'a H, mesh: &SurfaceMesh) -> Self {
        Self {
            complex,
            vertex_count: mesh.vertex_count(),
            edge_count: mesh.edge_count(),
            face_count: mesh.face_count(),
            potential_divergence: complex.potential_divergence(),
            co_potential_curl: complex.co_potential_curl(),
            co_potential_divergence: complex.co_potential_divergence(),
            potential_curl: complex.potential_curl(),
        }
    }

    /// Number of faces `F` (the rows have `2F` columns).
    pub fn face_count(&self) -> usize {
        self.face_count
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
        let finite = match constraint.target {
            Target::Vector(v) => v.iter().all(|x| x.is_finite()),
            Target::Divergence(s) | Target::Curl(s) => s.is_finite(),
        };
        if !finite {
            return Err(ConstraintError::NotFinite {
                id: id.clone(),
                what: "value",
                extra: "",
            });
        }
        self.check_location(id, constraint.location)?;
        let (rows, values) = match constraint.target {
            Target::Vector(v) => self.vector_rows(id, constraint.location, v)?,
            Target::Divergence(s) => {
                let space = match constraint.family {
                    OperatorFamily::Decomposition => Space::Potentials,
                    OperatorFamily::Other => Space::CoPotentials,
                };
                let row = self.scalar_row(constraint, "divergence", space)?;
                (vec![row], vec![s])
            }
            Target::Curl(s) => {
                let space = match constraint.family {
                    OperatorFamily::Decomposition => Space::CoPotentials,
                    OperatorFamily::Other => Space::Potentials,
                };
                let row = self.scalar_row(constraint, "curl", space)?;
                (vec![row], vec![s])
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

    fn check_location(&self, id: &str, location: Location) -> Result<(), ConstraintError> {
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
        match location {
            Location::Face { face, barycentric } => {
                range("face", face, self.face_count)?;
                if let Some(b) = barycentric {
                    check_barycentric(id, b)?;
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
        location: Location,
        value: [f64; 3],
    ) -> Result<(Vec<SparseRow>, Vec<f64>), ConstraintError> {
        let Location::Face { face, .. } = location else {
            return Err(ConstraintError::BadLocation {
                id: id.to_string(),
                problem: "a vector constraint needs a \"face\" (vectors are constant per face)"
                    .into(),
            });
        };
        let [e1, e2] = self.complex.fields().frame(face);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let rows = vec![vec![(2 * face, 1.0)], vec![(2 * face + 1, 1.0)]];
        Ok((rows, vec![dot(value, e1), dot(value, e2)]))
    }

    fn scalar_row(
        &self,
        constraint: &Constraint,
        kind: &'static str,
        space: Space,
    ) -> Result<SparseRow, ConstraintError> {
        let (matrix, dimension, name) = match (kind, space) {
            ("divergence", Space::Potentials) => (
                &self.potential_divergence,
                self.complex.potentials().dimension(),
                self.complex.potentials().name(),
            ),
            ("divergence", _) => (
                &self.co_potential_divergence,
                self.complex.co_potentials().dimension(),
                self.complex.co_potentials().name(),
            ),
            (_, Space::CoPotentials) => (
                &self.co_potential_curl,
                self.complex.co_potentials().dimension(),
                self.complex.co_potentials().name(),
            ),
            _ => (
                &self.potential_curl,
                self.complex.potentials().dimension(),
                self.complex.potentials().name(),
            ),
        };
        let weights: Vec<(usize, f64)> = match constraint.location {
            Location::Face { face, barycentric } => {
                let b = barycentric.unwrap_or([1.0 / 3.0; 3]);
                match space {
                    Space::Potentials => self.complex.potentials().interpolation_weights(face, b),
                    Space::CoPotentials => {
                        self.complex.co_potentials().interpolation_weights(face, b)
                    }
                }
            }
            Location::Vertex(node) => {
                self.check_node_kind(constraint, kind, name, dimension, "vertex")?;
                vec![(node, 1.0)]
            }
            Location::Edge(node) => {
                self.check_node_kind(constraint, kind, name, dimension, "edge")?;
                vec![(node, 1.0)]
            }
        };
        let mut row = BTreeMap::new();
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
        Ok(row.into_iter().filter(|&(_, a)| a != 0.0).collect())
    }

    fn check_node_kind(
        &self,
        constraint: &Constraint,
        kind: &'static str,
        space_name: &str,
        dimension: usize,
        given: &'static str,
    ) -> Result<(), ConstraintError> {
        let expected = if dimension == self.vertex_count {
            Some(("vertex", "vertices"))
        } else if dimension == self.edge_count {
            Some(("edge", "edges"))
        } else {
            None
        };
        match expected {
            Some((key, _)) if key == given => Ok(()),
            _ => {
                let (nodes_key, nodes) =
                    expected.unwrap_or(("face", "nodes that are neither vertices nor edges"));
                let other_family = match constraint.family {
                    OperatorFamily::Decomposition => OperatorFamily::Other,
                    OperatorFamily::Other => OperatorFamily::Decomposition,
                };
                Err(ConstraintError::NodeKindMismatch {
                    id: constraint.id.clone(),
                    detail: format!(
                        "the {} {kind} lives on the nodes of {space_name} ({nodes}), not on the {given} given; \
                         use \"{nodes_key}\" (or \"family\": \"{}\")",
                        constraint.family.name(),
                        other_family.name()
                    ),
                })
            }
        }
    }
}

/// Checks that `b` is finite, non-negative and sums to 1 (to 1e-9).
pub(crate) fn check_barycentric(id: &str, b: [f64; 3]) -> Result<(), ConstraintError> {
    let ok = b.iter().all(|x| x.is_finite() && *x >= 0.0)
        && (b.iter().sum::<f64>() - 1.0).abs() <= BARYCENTRIC_TOLERANCE;
    if ok {
        Ok(())
    } else {
        Err(ConstraintError::BadBarycentric {
            id: id.to_string(),
            values: b,
        })
    }
}
