//! [`ComplexParts`]: what every discrete Hodge decomposition consists of — the five matrices,
//! the nodes of its three spaces, its topology and a stable id — checked once for consistent
//! shapes, with the cache of the operators derived from them.

use super::{
    check_length, ComplexTopology, DiscretizationError, Mass, MassForm, MatrixHash, NodeSpace,
    OperatorCache,
};
use sprs::CsMat;
use std::sync::OnceLock;

/// The parts of a complex `potentials (n0) --d0--> fields (n1) --d1--> co-potentials (n2)` with
/// masses `M0`, `M1`, `M2` (see [`super::HodgeComplex`] for their meaning and units).
///
/// Built by [`ComplexParts::new`], which checks that the shapes fit together; immutable after
/// that, so that the derived operators in its [`OperatorCache`] always belong to these matrices.
/// To change one ingredient, build new parts ([`ComplexParts::with_co_potential_mass`]), which
/// come with a fresh cache.
#[derive(Debug, Clone)]
pub struct ComplexParts {
    id: String,
    d0: CsMat<f64>,
    d1: CsMat<f64>,
    masses: [Mass; 3],
    nodes: [NodeSpace; 3],
    topology: ComplexTopology,
    cache: OperatorCache,
    matrix_hash: OnceLock<MatrixHash>,
}

impl ComplexParts {
    /// The parts with id `id` (lower-case kebab-case, see [`super::HodgeComplex::id`]):
    /// `d0` (`n1 × n0`), `d1` (`n2 × n1`), `masses` `[M0, M1, M2]` and `nodes` (potentials,
    /// fields, co-potentials) of lengths `n0`, `n1`, `n2`. Each mass is restricted to the free
    /// nodes of its space (and a sparse one factored there: see [`Mass`]); `M1` must be stored
    /// directly ([`super::MassForm::Direct`]). Fails with
    /// [`DiscretizationError::DimensionMismatch`] if a shape does not fit,
    /// [`DiscretizationError::NotPositiveDefinite`] or [`DiscretizationError::NotPositive`] if a
    /// mass is not positive definite on its free nodes.
    pub fn new(
        id: impl Into<String>,
        d0: CsMat<f64>,
        d1: CsMat<f64>,
        masses: [Mass; 3],
        nodes: [NodeSpace; 3],
        topology: ComplexTopology,
    ) -> Result<Self, DiscretizationError> {
        let (n1, n0) = d0.shape();
        let n2 = d1.rows();
        let checks: [(&'static str, usize, usize); 7] = [
            ("columns of d1 (the rows of d0)", n1, d1.cols()),
            ("M0 (the columns of d0)", n0, masses[0].len()),
            ("M1 (the rows of d0)", n1, masses[1].len()),
            ("M2 (the rows of d1)", n2, masses[2].len()),
            ("potential nodes", n0, nodes[0].len()),
            ("field nodes", n1, nodes[1].len()),
            ("co-potential nodes", n2, nodes[2].len()),
        ];
        for (what, expected, found) in checks {
            check_length(what, expected, found)?;
        }
        check_mass_forms(&masses)?;
        let [m0, m1, m2] = masses;
        let masses = [
            m0.restricted_to(&nodes[0])?,
            m1.restricted_to(&nodes[1])?,
            m2.restricted_to(&nodes[2])?,
        ];
        Ok(Self {
            id: id.into(),
            d0,
            d1,
            masses,
            nodes,
            topology,
            cache: OperatorCache::default(),
            matrix_hash: OnceLock::new(),
        })
    }

    /// The same parts with id `id` and the co-potential mass `M2` replaced (same length), and
    /// a fresh cache: the smallest new discretization.
    pub fn with_co_potential_mass(
        &self,
        id: impl Into<String>,
        m2: Mass,
    ) -> Result<Self, DiscretizationError> {
        let [m0, m1, _] = self.masses.clone();
        Self::new(
            id,
            self.d0.clone(),
            self.d1.clone(),
            [m0, m1, m2],
            self.nodes.clone(),
            self.topology,
        )
    }

    /// The same parts under id `id`, with a fresh cache: the matrices, nodes and topology bit
    /// for bit.
    pub fn renamed(&self, id: impl Into<String>) -> Self {
        Self {
            id: id.into(),
            d0: self.d0.clone(),
            d1: self.d1.clone(),
            masses: self.masses.clone(),
            nodes: self.nodes.clone(),
            topology: self.topology,
            cache: OperatorCache::default(),
            matrix_hash: OnceLock::new(),
        }
    }

    /// The id.
    pub fn id(&self) -> &str {
        &self.id
    }

    /// `d0` (`n1 × n0`).
    pub fn d0(&self) -> &CsMat<f64> {
        &self.d0
    }

    /// `d1` (`n2 × n1`).
    pub fn d1(&self) -> &CsMat<f64> {
        &self.d1
    }

    /// `M0` (`n0 × n0`).
    pub fn m0(&self) -> &Mass {
        &self.masses[0]
    }

    /// `M1` (`n1 × n1`).
    pub fn m1(&self) -> &Mass {
        &self.masses[1]
    }

    /// `M2` (`n2 × n2`).
    pub fn m2(&self) -> &Mass {
        &self.masses[2]
    }

    /// The potential nodes (`n0`).
    pub fn potential_nodes(&self) -> &NodeSpace {
        &self.nodes[0]
    }

    /// The field nodes (`n1`).
    pub fn field_nodes(&self) -> &NodeSpace {
        &self.nodes[1]
    }

    /// The co-potential nodes (`n2`).
    pub fn co_potential_nodes(&self) -> &NodeSpace {
        &self.nodes[2]
    }

    /// Components, harmonic dimension and boundary.
    pub fn topology(&self) -> &ComplexTopology {
        &self.topology
    }

    /// The cache of the derived operators.
    pub fn operator_cache(&self) -> &OperatorCache {
        &self.cache
    }

    /// The hashes of the five matrices and the fixed nodes ([`MatrixHash`]), computed on first
    /// use and kept (the parts are immutable).
    pub fn matrix_hash(&self) -> MatrixHash {
        *self.matrix_hash.get_or_init(|| MatrixHash::of(self))
    }
}

/// The forms tvf computes with: `M0` and `M1` given directly (their inverses are solved, never
/// formed), and `M2` diagonal or given by its sparse inverse, the co-potential mass (a sparse
/// `M2` given directly would make the co-potential mass, the mass of the co-exact eigenproblem,
/// dense).
fn check_mass_forms(masses: &[Mass; 3]) -> Result<(), DiscretizationError> {
    for (mass, name) in masses[..2].iter().zip(["M0", "M1"]) {
        if mass.form() != MassForm::Direct {
            return Err(DiscretizationError::Inconsistent(format!(
                "{}: the mass {name} must be given directly, not as its inverse",
                mass.what()
            )));
        }
    }
    let m2 = &masses[2];
    if !m2.is_diagonal() && m2.form() == MassForm::Direct {
        return Err(DiscretizationError::Inconsistent(format!(
            "{}: a sparse M2 must be given as its inverse, the co-potential mass (M2 itself has a \
             dense inverse, which tvf does not form)",
            m2.what()
        )));
    }
    Ok(())
}
