//! [`GalerkinBlocks`]: the sparse pieces of the energies of a complex whose masses are not all
//! diagonal (consistent P1 masses, the Whitney 1-form mass, a co-potential mass stored as its
//! inverse), and the exact application of those energies through mass solves.

use sprs::{CsMat, TriMat};
use tvf_core::discretization::sparse::{mul_vec, product, to_csr, transpose};
use tvf_core::discretization::{HodgeComplex, Mass, NodeKind, NodeSpace};
use tvf_solvers::iterative_refinement::{symmetric_product, DoubleDouble};

/// The free nodes of a space ([`NodeSpace::is_free`]): the nodes that carry unknowns.
#[derive(Debug, Clone)]
pub(crate) struct FreeNodes {
    /// Full index of every free node, ascending.
    pub full: Vec<usize>,
    /// Position of every node among the free ones (`usize::MAX` for a fixed node).
    pub position: Vec<usize>,
}

impl FreeNodes {
    /// The free nodes of `nodes`.
    pub(crate) fn of(nodes: &NodeSpace) -> Self {
        let full: Vec<usize> = (0..nodes.len()).filter(|&i| nodes.is_free(i)).collect();
        let mut position = vec![usize::MAX; nodes.len()];
        for (k, &i) in full.iter().enumerate() {
            position[i] = k;
        }
        Self { full, position }
    }

    /// Number of free nodes.
    pub(crate) fn len(&self) -> usize {
        self.full.len()
    }

    /// Number of nodes of the space.
    pub(crate) fn space_len(&self) -> usize {
        self.position.len()
    }

    /// The free entries of `v` (space length in, free count out).
    pub(crate) fn gather(&self, v: &[f64]) -> Vec<f64> {
        self.full.iter().map(|&i| v[i]).collect()
    }

    /// `v` (free count) placed at the free nodes, zero elsewhere.
    pub(crate) fn scatter(&self, v: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.space_len()];
        for (&i, &x) in self.full.iter().zip(v) {
            out[i] = x;
        }
        out
    }

    /// A sparse row over the space's nodes restricted to the free ones (positions), in order.
    pub(crate) fn restrict_row(&self, row: &[(usize, f64)]) -> Vec<(usize, f64)> {
        row.iter()
            .filter_map(|&(i, a)| match self.position.get(i) {
                Some(&k) if k != usize::MAX => Some((k, a)),
                _ => None,
            })
            .collect()
    }
}

/// Which scalar space an auxiliary unknown lives in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum AuxKind {
    /// Potential nodes: `p = M0⁻¹ d0ᵀ M1 x` (minus the pointwise divergence).
    Potential,
    /// Co-potential nodes: `q = M2 d1 x` (the pointwise curl).
    CoPotential,
}

/// A space whose term `Rᵀ D⁻¹ R` of the Dirichlet energy is not kept as a sparse matrix: its
/// nodal quantity `D⁻¹ R x` becomes an auxiliary unknown of the augmented systems.
///
/// Potentials: `R = d0ᵀ M1`, `D = M0`, where `M0` is stored directly and is sparse (`M0⁻¹`
/// dense). Co-potentials: `R = d1`, `D = M2⁻¹`, where the co-potential mass is
/// stored as its sparse inverse (`M2` dense). Both restricted to the free nodes of the space
/// (rows) and of the fields (columns).
#[derive(Debug, Clone)]
pub(crate) struct AuxSpace {
    pub kind: AuxKind,
    pub nodes: FreeNodes,
    /// `R` (`m × n1f`, CSR; `m` free nodes of the space, `n1f` free field nodes).
    pub coupling: CsMat<f64>,
    /// `Rᵀ` (`n1f × m`, CSR).
    pub coupling_transpose: CsMat<f64>,
    /// `D` (`m × m`, CSR, symmetric positive definite).
    pub mass: CsMat<f64>,
    /// The mass whose [`Mass::solve`] is `D⁻¹` (on the space's full index range).
    inverse: Mass,
}

impl AuxSpace {
    /// `D⁻¹ v` (`m` values in and out), through the mass's cached Cholesky factorization.
    pub(crate) fn solve(&self, v: &[f64]) -> Vec<f64> {
        self.nodes
            .gather(&self.inverse.solve(&self.nodes.scatter(v)))
    }
}

/// The weights of an energy `A = τ M1 + α S + β S M1⁻¹ S` (`τ, α, β ≥ 0`; soft design:
/// `τ = ε`, `α = 1`, `β = ω`; the reference spline: `τ = ε`, `α = ω`, `β = 1`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct EnergyWeights {
    /// `τ`, the screening weight (1/length²).
    pub screening: f64,
    /// `α`, the weight of the Dirichlet energy `S`.
    pub dirichlet: f64,
    /// `β`, the weight of the biharmonic energy `S M1⁻¹ S` (length²).
    pub biharmonic: f64,
}

/// The sparse pieces of `S = M1 d0 M0⁻¹ d0ᵀ M1 + d1ᵀ M2 d1` and of `M1`, restricted to the free
/// field nodes (`n1f` of the `n1`; a field is zero on the others):
///
/// - `direct`: the terms of `S` kept as sparse matrices (a mass with a sparse inverse in the
///   middle: a diagonal, a potential mass stored as its inverse, or a co-potential mass stored
///   directly);
/// - `aux`: the other terms, `Rᵀ D⁻¹ R` per [`AuxSpace`];
/// - `field_mass`: `M1` (diagonal or sparse).
///
/// `S = direct + Σ Rᵀ D⁻¹ R` on the free field nodes, as the seam's composed
/// [`HodgeOperators::dirichlet_energy`](tvf_core::discretization::HodgeOperators::dirichlet_energy)
/// restricted there.
#[derive(Debug, Clone)]
pub(crate) struct GalerkinBlocks {
    pub field: FreeNodes,
    /// Terms of `S` that are sparse (`n1f × n1f`, CSR, exactly symmetric).
    pub direct: CsMat<f64>,
    /// `M1` (`n1f × n1f`, CSR, symmetric).
    pub field_mass: CsMat<f64>,
    /// The spaces whose term of `S` goes through auxiliary unknowns.
    pub aux: Vec<AuxSpace>,
    /// Group of every free field node for the orderings (a face for face-frame fields, else the
    /// node itself), and the number of groups.
    pub field_groups: (Vec<usize>, usize),
    m1: Mass,
}

impl GalerkinBlocks {
    /// The blocks of `complex`.
    pub(crate) fn new<H: HodgeComplex + ?Sized>(complex: &H) -> Self {
        let field = FreeNodes::of(complex.field_nodes());
        let m1 = complex.m1().clone();
        let m1_matrix = m1.stored_matrix();
        let (m0, m2) = (complex.m0(), complex.m2());
        let (d0, d1) = (complex.d0(), complex.d1());
        let n1f = field.len();
        let mut direct: CsMat<f64> = CsMat::zero((n1f, n1f));
        let mut aux = Vec::new();
        // Wherever M0⁻¹ is sparse its term stays in the field block, also with a sparse M1
        // (polygon-dec), although M1 d0 M0⁻¹ d0ᵀ M1 couples fields farther than d0ᵀ M1 does
        // (3× the factorization's flops on a quad torus): through p instead, the field block is
        // singular up to εM1 on every gradient, the factorization meets pivots of that size,
        // and its solves are wrong in the fourth digit (see `crate::augmented_system`).
        match m0.sparse_inverse_matrix() {
            Some(m0_inverse) => {
                // M1 d0 M0⁻¹ d0ᵀ M1.
                let gradient = product(&m1_matrix, d0);
                let term = product(&product(&gradient, &m0_inverse), &transpose(&gradient));
                direct = &direct + &restricted(&term, &field, &field);
            }
            None => aux.push(AuxSpace::new(
                AuxKind::Potential,
                &product(&transpose(d0), &m1_matrix),
                &m0.stored_matrix(),
                m0.clone(),
                FreeNodes::of(complex.potential_nodes()),
                &field,
            )),
        }
        match m2.sparse_matrix() {
            Some(m2_matrix) => {
                // d1ᵀ M2 d1.
                let term = product(&product(&transpose(d1), &m2_matrix), d1);
                direct = &direct + &restricted(&term, &field, &field);
            }
            None => aux.push(AuxSpace::new(
                AuxKind::CoPotential,
                d1,
                &m2.stored_matrix(),
                m2.inverse(),
                FreeNodes::of(complex.co_potential_nodes()),
                &field,
            )),
        }
        let direct = (&direct + &transpose(&direct)).map(|x| 0.5 * x);
        let field_groups = field_groups(complex.field_nodes(), &field);
        Self {
            field_mass: restricted(&m1_matrix, &field, &field),
            field,
            direct: to_csr(&direct),
            aux,
            field_groups,
            m1,
        }
    }

    /// Number of free field nodes `n1f`.
    pub(crate) fn field_len(&self) -> usize {
        self.field.len()
    }

    /// `S x` (`n1f` values in and out).
    pub(crate) fn dirichlet(&self, x: &[f64]) -> Vec<f64> {
        let mut y = mul_vec(&self.direct, x);
        for space in &self.aux {
            let nodal = space.solve(&mul_vec(&space.coupling, x));
            for (yi, v) in y.iter_mut().zip(mul_vec(&space.coupling_transpose, &nodal)) {
                *yi += v;
            }
        }
        y
    }

    /// `M1⁻¹ v` (`n1f` values in and out), through the seam's mass solve.
    pub(crate) fn field_mass_solve(&self, v: &[f64]) -> Vec<f64> {
        self.field.gather(&self.m1.solve(&self.field.scatter(v)))
    }

    /// `A x = τ M1 x + α S x + β S M1⁻¹ S x` (`n1f` values in and out), `B` never formed.
    pub(crate) fn energy(&self, weights: EnergyWeights, x: &[f64]) -> Vec<f64> {
        let sx = self.dirichlet(x);
        let mut y: Vec<f64> = mul_vec(&self.field_mass, x)
            .iter()
            .zip(&sx)
            .map(|(m, s)| weights.screening * m + weights.dirichlet * s)
            .collect();
        if weights.biharmonic > 0.0 {
            let bx = self.dirichlet(&self.field_mass_solve(&sx));
            for (yi, v) in y.iter_mut().zip(bx) {
                *yi += weights.biharmonic * v;
            }
        }
        y
    }

    /// `A x` as in [`GalerkinBlocks::energy`], carried in double-double: every sparse product
    /// and sum keeps its rounding error; the mass solves (`M0⁻¹`, `M2`, `M1⁻¹`) are applied to
    /// the high and the low parts separately in `f64` (their relative error is the rounding
    /// error times the condition number of the mass, a small constant for the masses of a mesh).
    pub(crate) fn accurate_energy(
        &self,
        weights: EnergyWeights,
        x: &[DoubleDouble],
    ) -> Vec<DoubleDouble> {
        let sx = self.accurate_dirichlet(x);
        let mx = symmetric_product(&self.field_mass, x);
        let mut y: Vec<DoubleDouble> = mx
            .into_iter()
            .zip(&sx)
            .map(|(m, &s)| {
                let mut sum = DoubleDouble::default();
                sum.add_product(weights.screening, m);
                sum.add_product(weights.dirichlet, s);
                sum
            })
            .collect();
        if weights.biharmonic > 0.0 {
            let solved = split_solve(&sx, |v| self.field_mass_solve(v));
            for (yi, v) in y.iter_mut().zip(self.accurate_dirichlet(&solved)) {
                yi.add_product(weights.biharmonic, v);
            }
        }
        y
    }

    /// `S x` in double-double (see [`GalerkinBlocks::accurate_energy`]).
    fn accurate_dirichlet(&self, x: &[DoubleDouble]) -> Vec<DoubleDouble> {
        let mut y = symmetric_product(&self.direct, x);
        for space in &self.aux {
            let nodal = split_solve(&symmetric_product(&space.coupling, x), |v| space.solve(v));
            for (yi, v) in y
                .iter_mut()
                .zip(symmetric_product(&space.coupling_transpose, &nodal))
            {
                yi.add(v);
            }
        }
        y
    }
}

impl AuxSpace {
    fn new(
        kind: AuxKind,
        coupling: &CsMat<f64>,
        mass: &CsMat<f64>,
        inverse: Mass,
        nodes: FreeNodes,
        field: &FreeNodes,
    ) -> Self {
        let coupling = to_csr(&restricted(coupling, &nodes, field));
        Self {
            kind,
            coupling_transpose: to_csr(&transpose(&coupling)),
            coupling,
            mass: to_csr(&restricted(mass, &nodes, &nodes)),
            inverse,
            nodes,
        }
    }
}

/// `f(hi) + f(lo)` for a linear `f` applied in `f64` to both parts of a double-double vector,
/// renormalised.
fn split_solve(v: &[DoubleDouble], f: impl Fn(&[f64]) -> Vec<f64>) -> Vec<DoubleDouble> {
    let hi: Vec<f64> = v.iter().map(|x| x.hi).collect();
    let lo: Vec<f64> = v.iter().map(|x| x.lo).collect();
    f(&hi)
        .into_iter()
        .zip(f(&lo))
        .map(|(h, l)| {
            let mut sum = DoubleDouble { hi: h, lo: 0.0 };
            sum.add(DoubleDouble { hi: l, lo: 0.0 });
            sum
        })
        .collect()
}

/// `matrix` restricted to the free `rows` and `cols` (positions), CSR.
fn restricted(matrix: &CsMat<f64>, rows: &FreeNodes, cols: &FreeNodes) -> CsMat<f64> {
    let mut triplets = TriMat::new((rows.len(), cols.len()));
    for (&value, (i, j)) in matrix.iter() {
        let (r, c) = (rows.position[i], cols.position[j]);
        if r != usize::MAX && c != usize::MAX {
            triplets.add_triplet(r, c, value);
        }
    }
    triplets.to_csr()
}

/// The ordering group of every free field node: its face for face-frame fields (the two
/// coefficients of a face couple to the same nodes), else the node itself; numbered densely.
fn field_groups(nodes: &NodeSpace, field: &FreeNodes) -> (Vec<usize>, usize) {
    let element = |i: usize| match nodes.kind {
        NodeKind::FaceFrames => i / 2,
        _ => i,
    };
    let mut number = vec![usize::MAX; nodes.len()];
    let mut count = 0;
    let groups = field
        .full
        .iter()
        .map(|&i| {
            let e = element(i);
            if number[e] == usize::MAX {
                number[e] = count;
                count += 1;
            }
            number[e]
        })
        .collect();
    (groups, count)
}
