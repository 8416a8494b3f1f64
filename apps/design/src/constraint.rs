//! The constraint model: what a user prescribes (a vector, a divergence or a curl value), where,
//! and in which operator family.

use crate::DesignError;

/// What a constraint prescribes. All values are **pointwise** (`docs/conventions.md`): a tangent vector, or the
/// pointwise divergence / curl of the field (units 1/length times the field's units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// A vector in a face, given in 3D; only its projection onto the face plane is prescribed
    /// (2 constraint rows: the identity in the face frame).
    Vector([f64; 3]),
    /// A divergence value (a source for positive values, a sink for negative ones); 1 row.
    Divergence(f64),
    /// A curl value (a vortex, counter-clockwise seen from outside for positive values); 1 row.
    Curl(f64),
}

impl Target {
    /// Whether every prescribed number is finite.
    pub fn is_finite(&self) -> bool {
        match self {
            Target::Vector(v) => v.iter().all(|x| x.is_finite()),
            Target::Divergence(s) | Target::Curl(s) => s.is_finite(),
        }
    }

    /// Lower-case name used in JSON: `vector`, `divergence`, `curl`.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Target::Vector(_) => "vector",
            Target::Divergence(_) => "divergence",
            Target::Curl(_) => "curl",
        }
    }
}

/// Where a constraint applies.
#[derive(Debug, Clone, PartialEq)]
pub enum Location {
    /// Face `face`, optionally at the point with weights `barycentric` over the face's corners
    /// (one per corner, in the face's corner order, non-negative, summing to 1: a triangle's
    /// barycentric coordinates, a polygon's generalised ones — the weights of a
    /// [`tvf_core::SurfacePoint`]). A vector constraint is the same at every point of its face
    /// for face fields; a divergence or curl at a point mixes the nodal rows with the
    /// interpolation weights of the family's function space (face centroid when `barycentric`
    /// is absent).
    Face {
        /// Face index.
        face: usize,
        /// Weights of the point over the face's corners, if any.
        barycentric: Option<Vec<f64>>,
    },
    /// A mesh vertex: a node of the Lagrange P1 space.
    Vertex(usize),
    /// A mesh edge (numbered as in [`tvf_core::SurfaceMesh::edges`]): a node of the
    /// Crouzeix–Raviart space.
    Edge(usize),
}

/// Which divergence / curl operator a scalar constraint uses.
///
/// The decomposition's own pair vanishes on the harmonic fields: divergence in the potential
/// space (`potential_divergence`), curl in the co-potential space (`co_potential_curl`). For the
/// conforming complex that is divergence at vertices (P1) and curl at edges (CR); for the
/// nonconforming complex the other way round. [`OperatorFamily::Other`] selects the other pair
/// (`co_potential_divergence`, `potential_curl`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum OperatorFamily {
    /// The decomposition's own divergence and curl (the default).
    #[default]
    Decomposition,
    /// The other family.
    Other,
}

impl OperatorFamily {
    /// Name used in JSON: `decomposition` or `other`.
    pub fn name(self) -> &'static str {
        match self {
            OperatorFamily::Decomposition => "decomposition",
            OperatorFamily::Other => "other",
        }
    }
}

/// One user constraint: an id (unique within a set), a target, a location, the operator family
/// (for divergence and curl) and a weight (used by soft design only; hard splines ignore it).
#[derive(Debug, Clone, PartialEq)]
pub struct Constraint {
    /// Unique name, used in every error and report.
    pub id: String,
    /// The prescribed value.
    pub target: Target,
    /// Where it applies.
    pub location: Location,
    /// Operator family of a divergence or curl constraint (ignored for vectors).
    pub family: OperatorFamily,
    /// Soft-design weight `w > 0`: the constraint's rows enter `C̃` scaled by `√w`. Default 1.
    pub weight: f64,
}

impl Constraint {
    /// A constraint with the default family and weight 1.
    pub fn new(id: impl Into<String>, target: Target, location: Location) -> Self {
        Self {
            id: id.into(),
            target,
            location,
            family: OperatorFamily::Decomposition,
            weight: 1.0,
        }
    }

    /// The same constraint with another operator family.
    pub fn with_family(mut self, family: OperatorFamily) -> Self {
        self.family = family;
        self
    }
}

/// A sparse row: `(index, value)` pairs with distinct indices. Over the field coefficients
/// (`n1` columns) unless said otherwise.
pub type SparseRow = Vec<(usize, f64)>;

/// What a constraint row is made of, in terms of the complex's nodal quantities.
///
/// The pointwise divergence of the decomposition is `−M0⁻¹ d0ᵀ M1` and its curl `M2 d1`; where
/// `M0` is not diagonal (a consistent P1 mass) or `M2` is dense (a consistent co-potential mass
/// stored as `M2⁻¹`), their rows are dense over the field coefficients. The full soft design
/// ([`crate::FullSoftDesign`]) then keeps the nodal quantities `M0⁻¹ d0ᵀ M1 x` and `M2 d1 x` as
/// unknowns of its sparse system and reads such a row as the sparse combination `a` of them.
#[derive(Debug, Clone, PartialEq)]
pub enum RowOrigin {
    /// A combination of field coefficients that is sparse: a sampled vector, or the other
    /// family's divergence or curl where its operator is a sparse matrix.
    Field,
    /// `Σ_j a_j (M0⁻¹ d0ᵀ M1)_j`, `a` over the potential nodes: a divergence of the
    /// decomposition family (`a` is minus the interpolation weights of the point or node).
    Potential(SparseRow),
    /// `Σ_j a_j (M2 d1)_j`, `a` over the co-potential nodes: a curl of the decomposition family
    /// (`a` is the interpolation weights).
    CoPotential(SparseRow),
    /// A row of a composed operator that is neither of the above (the other family's divergence
    /// or curl where a mass it inverts is not diagonal): dense over the field coefficients.
    Composed,
}

/// A constraint turned into linear rows over the field coefficients: `rows[k] · x = values[k]`.
///
/// Rows are **pointwise** (a row of the pointwise divergence, curl or identity), so residuals are
/// in the units of the prescribed values. Every row is complete over the `n1` field coefficients:
/// sparse where the operator is a sparse matrix, dense where the operator is composed (an inverse
/// of a non-diagonal mass inside; see [`RowOrigin`]). The reduced solvers only need `rows[k] U`,
/// which a dense row gives as well.
#[derive(Debug, Clone, PartialEq)]
pub struct CompiledConstraint {
    /// The constraint's id.
    pub id: String,
    /// 2 rows for a vector, 1 for a divergence or curl.
    pub rows: Vec<SparseRow>,
    /// Prescribed values, one per row.
    pub values: Vec<f64>,
    /// Soft-design weight (rows are scaled by `√weight` in soft design only).
    pub weight: f64,
    /// What each row is made of (one per row).
    pub origins: Vec<RowOrigin>,
}

impl CompiledConstraint {
    /// Replaces the prescribed values (same rows): as many as before, all finite.
    pub fn set_values(&mut self, values: &[f64]) -> Result<(), DesignError> {
        if values.len() != self.values.len() {
            return Err(DesignError::DimensionMismatch {
                what: "constraint values",
                expected: self.values.len(),
                actual: values.len(),
            });
        }
        if let Some(&value) = values.iter().find(|v| !v.is_finite()) {
            return Err(DesignError::BadParameter {
                what: "constraint value",
                value,
            });
        }
        self.values.copy_from_slice(values);
        Ok(())
    }

    /// Residuals `rows[k] · x − values[k]` for a field `x` (`n1` coefficients).
    pub fn residuals(&self, field: &[f64]) -> Vec<f64> {
        self.rows
            .iter()
            .zip(&self.values)
            .map(|(row, value)| row.iter().map(|&(j, a)| a * field[j]).sum::<f64>() - value)
            .collect()
    }

    /// Scale of the prescribed values (Euclidean norm), for relative residuals.
    pub fn value_scale(&self) -> f64 {
        self.values.iter().map(|v| v * v).sum::<f64>().sqrt()
    }
}

/// The entries `(i, j)` (both triangles) of `C̃ᵀ W C̃` for a set of constraints.
pub(crate) fn constraint_gram_entries(
    constraints: &[CompiledConstraint],
) -> Vec<(usize, usize, f64)> {
    let mut entries = Vec::new();
    for c in constraints {
        for row in &c.rows {
            for &(i, a) in row {
                for &(j, b) in row {
                    entries.push((i, j, c.weight * a * b));
                }
            }
        }
    }
    entries
}
