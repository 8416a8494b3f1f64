//! [`AugmentedFactor`]: the sparse symmetric system whose Schur complement on the field is the
//! energy `A = T + α S + β S M1⁻¹ S` of a complex whose masses are not all diagonal, and its
//! sparse `LDLᵀ` factorization. `S` (through `M0⁻¹` or a dense `M2`) and `B = S M1⁻¹ S` are
//! dense there; the system has only the sparsity of `d0`, `d1` and the masses.

use crate::constraint::SparseRow;
use crate::error::DesignError;
use crate::galerkin_blocks::{EnergyWeights, GalerkinBlocks};
use crate::soft_system::Factoring;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::{SparseColMat, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::Mat;
use sprs::{CsMat, TriMat};
use std::collections::BTreeSet;
use tvf_solvers::convert::upper_triangle_csc;
use tvf_solvers::ordering::{nested_dissection_of_groups, AdjacencyGraph};
use tvf_solvers::{FillOrdering, SolverError, SparseLdlt};

/// Constraint terms of a soft design, each kept where it is sparse.
#[derive(Debug, Clone, Default)]
pub(crate) struct ConstraintTerms {
    /// `w a aᵀ` of the rows that are sparse over the field: `(i, j, value)` over the free field
    /// nodes, both triangles.
    pub field: Vec<(usize, usize, f64)>,
    /// Per auxiliary space (as in [`GalerkinBlocks::aux`]): `w a aᵀ` of the rows that are sparse
    /// combinations `a` of that space's nodal quantities `D⁻¹ R x`, both triangles.
    pub aux: Vec<Vec<(usize, usize, f64)>>,
    /// Rows that are dense over the field (a composed operator): the row over the free field
    /// nodes and its weight `w > 0`.
    pub dense: Vec<(SparseRow, f64)>,
}

/// The constraint entries the pattern keeps, present or not (explicit zeros where a constraint
/// left), so that changing the constraints refactors with the same symbolic analysis.
#[derive(Debug, Clone, Default)]
pub(crate) struct PatternUnion {
    field: BTreeSet<(usize, usize)>,
    aux: Vec<BTreeSet<(usize, usize)>>,
}

impl PatternUnion {
    /// Adds the entries of `terms`.
    pub(crate) fn include(&mut self, terms: &ConstraintTerms) {
        self.field
            .extend(terms.field.iter().map(|&(i, j, _)| (i, j)));
        self.aux.resize_with(terms.aux.len(), BTreeSet::new);
        for (set, entries) in self.aux.iter_mut().zip(&terms.aux) {
            set.extend(entries.iter().map(|&(i, j, _)| (i, j)));
        }
    }
}

/// Where the unknowns of the augmented system are: `x` (`n1f`), `y` (`n1f`, when `β > 0`), per
/// auxiliary space its `p` (`m`) then its `s` (`m`), then one `λ` per dense row.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Layout {
    fields: usize,
    biharmonic: bool,
    /// First unknown of each auxiliary space's `p` block and its size `m`.
    aux: Vec<(usize, usize)>,
    /// First `λ`.
    dense: usize,
    total: usize,
}

impl Layout {
    fn new(blocks: &GalerkinBlocks, biharmonic: bool, dense_rows: usize) -> Self {
        let fields = blocks.field_len();
        let mut next = if biharmonic { 2 * fields } else { fields };
        let aux = blocks
            .aux
            .iter()
            .map(|space| {
                let first = next;
                next += 2 * space.nodes.len();
                (first, space.nodes.len())
            })
            .collect();
        Self {
            fields,
            biharmonic,
            aux,
            dense: next,
            total: next + dense_rows,
        }
    }

    /// Expected pivots: positive on `x` and every `p`, negative on `y`, every `s` and every `λ`.
    fn inertia(&self) -> (usize, usize) {
        let nodal: usize = self.aux.iter().map(|&(_, m)| m).sum();
        let y = if self.biharmonic { self.fields } else { 0 };
        (self.fields + nodal, y + nodal + (self.total - self.dense))
    }
}

/// The factored augmented system (see [`assemble`]).
#[derive(Debug)]
pub(crate) struct AugmentedFactor {
    factor: SparseLdlt,
    layout: Layout,
}

impl AugmentedFactor {
    /// Orders (groups of unknowns, see [`elimination_order`]) and factors `upper` (from
    /// [`assemble`]); checks the inertia.
    pub(crate) fn new(
        upper: &SparseColMat<usize, f64>,
        layout: Layout,
        blocks: &GalerkinBlocks,
        factoring: Factoring,
    ) -> Result<Self, DesignError> {
        let permutation = elimination_order(upper, &layout, blocks, factoring.ordering)?;
        let factor =
            SparseLdlt::with_permutation_and_parallelism(upper.as_ref(), &permutation, |flops| {
                factoring.parallelism.choose(flops)
            })
            .map_err(not_definite)?;
        check_inertia(&factor, &layout)?;
        Ok(Self { factor, layout })
    }

    /// Refactors numerically when `upper` has the analysed pattern and layout; returns `false`
    /// (and changes nothing) when it does not.
    pub(crate) fn refactor(
        &mut self,
        upper: &SparseColMat<usize, f64>,
        layout: &Layout,
    ) -> Result<bool, DesignError> {
        if *layout != self.layout || !self.factor.same_pattern(upper.as_ref()) {
            return Ok(false);
        }
        self.factor.refactor(upper.as_ref()).map_err(not_definite)?;
        check_inertia(&self.factor, &self.layout)?;
        Ok(true)
    }

    /// `A⁻¹ r` for the field energy `A` the system was assembled for (`n1f` values in and out):
    /// the field part of the solution of the augmented system with right-hand side `(r, 0)`.
    pub(crate) fn solve_field(&self, r: &[f64]) -> Vec<f64> {
        let mut rhs = Mat::zeros(self.layout.total, 1);
        for (i, &v) in r.iter().enumerate() {
            rhs[(i, 0)] = v;
        }
        self.factor.solve_in_place(rhs.as_mut());
        (0..self.layout.fields).map(|i| rhs[(i, 0)]).collect()
    }

    /// The factorization.
    pub(crate) fn ldlt(&self) -> &SparseLdlt {
        &self.factor
    }
}

/// Upper triangle (CSC, sorted rows) of the augmented system for the energy of `weights`
/// (`τ = screening`, `α = dirichlet > 0`, `β = biharmonic`) plus `terms`, with the pattern of
/// `union` (which must hold the entries of `terms`):
///
/// ```text
///        x               y              p                s       λ
/// x [ T + α S_d       √β S_d           0              √α Rᵀ    g   ]
/// y [ √β S_d          −M1             √(β/α) Rᵀ        0       0   ]
/// p [ 0               √(β/α) R        D + W_p/α       −D       0   ]
/// s [ √α R            0               −D               0       0   ]
/// λ [ gᵀ              0                0               0     −1/w  ]
/// ```
///
/// with `T = τ M1 + C̃ᵀ W C̃` (sparse rows), `S_d` the sparse terms of `S`, and per auxiliary
/// space its `R`, `D` ([`crate::galerkin_blocks::AuxSpace`]) and `W_p` (its constraint terms).
/// Eliminating `(p, s)` gives `[[T + α S, √β S], [√β S, −M1]]` on `(x, y)` (`S = S_d + Rᵀ D⁻¹ R`:
/// the block `[[D + W_p/α, −D], [−D, 0]]` inverts to `[[0, −D⁻¹], [−D⁻¹, −D⁻¹(D + W_p/α)D⁻¹]]`),
/// then `y` gives `A = T + α S + β S M1⁻¹ S + (D⁻¹R)ᵀ W_p (D⁻¹R)`, and every `λ` adds `w g gᵀ`.
/// In the solution `p = √α D⁻¹ R x` (for potentials minus the divergence, for co-potentials the
/// curl), `y = √β M1⁻¹ S x` and `λ = w (g·x)` for a zero right-hand side below `x`.
///
/// The unknowns `x, p` form a positive definite block (`T + α S_d ≻ 0`, `D ≻ 0`) and
/// `y, s, λ` a negative semi-definite one (`−M1`, `0`, `−1/w`); the `s` block is zero, so the
/// system is not quasi-definite, but every leading principal submatrix of an elimination order
/// that takes each `p_i` before its `s_i` is nonsingular with as many negative eigenvalues as
/// negative unknowns (the coupling `−D` of the `s` in it to their `p` is nonsingular): such an
/// `LDLᵀ` exists, with positive pivots on `x, p` and negative ones on `y, s, λ`.
pub(crate) fn assemble(
    blocks: &GalerkinBlocks,
    weights: EnergyWeights,
    terms: &ConstraintTerms,
    union: &PatternUnion,
) -> Result<(SparseColMat<usize, f64>, Layout), DesignError> {
    let layout = Layout::new(blocks, weights.biharmonic > 0.0, terms.dense.len());
    let n = layout.fields;
    let (alpha, beta) = (weights.dirichlet, weights.biharmonic);
    let mut t = TriMat::new((layout.total, layout.total));
    for (&v, (i, j)) in blocks.field_mass.iter() {
        symmetric(&mut t, 0, i, j, weights.screening * v);
    }
    for (&v, (i, j)) in blocks.direct.iter() {
        symmetric(&mut t, 0, i, j, alpha * v);
    }
    for &(i, j, v) in &terms.field {
        symmetric(&mut t, 0, i, j, v);
    }
    for &(i, j) in &union.field {
        symmetric(&mut t, 0, i, j, 0.0);
    }
    if layout.biharmonic {
        for (&v, (i, j)) in blocks.direct.iter() {
            t.add_triplet(i, n + j, beta.sqrt() * v);
        }
        for (&v, (i, j)) in blocks.field_mass.iter() {
            symmetric(&mut t, n, i, j, -v);
        }
    }
    for (a, (space, &(p, m))) in blocks.aux.iter().zip(&layout.aux).enumerate() {
        let s = p + m;
        for (&v, (i, j)) in space.coupling.iter() {
            t.add_triplet(j, s + i, alpha.sqrt() * v);
            if layout.biharmonic {
                t.add_triplet(n + j, p + i, (beta / alpha).sqrt() * v);
            }
        }
        for (&v, (i, j)) in space.mass.iter() {
            t.add_triplet(p + i, s + j, -v);
            symmetric(&mut t, p, i, j, v);
        }
        for &(i, j, v) in terms.aux.get(a).into_iter().flatten() {
            symmetric(&mut t, p, i, j, v / alpha);
        }
        for &(i, j) in union.aux.get(a).into_iter().flatten() {
            symmetric(&mut t, p, i, j, 0.0);
        }
        for i in 0..m {
            t.add_triplet(s + i, s + i, 0.0);
        }
    }
    for (k, (row, w)) in terms.dense.iter().enumerate() {
        let lambda = layout.dense + k;
        for &(j, g) in row {
            t.add_triplet(j, lambda, g);
        }
        t.add_triplet(lambda, lambda, -1.0 / w);
    }
    let matrix: CsMat<f64> = t.to_csc();
    let upper = upper_triangle_csc(&matrix).map_err(|e| match e {
        SolverError::NonFinite {
            row, col, value, ..
        } => DesignError::Solver(SolverError::NonFinite {
            context: "soft-design system",
            row,
            col,
            value,
        }),
        other => DesignError::Solver(other),
    })?;
    Ok((upper, layout))
}

/// Entry `(offset + i, offset + j)` of a symmetric block given in full storage, kept on the
/// upper triangle only.
fn symmetric(t: &mut TriMat<f64>, offset: usize, i: usize, j: usize, v: f64) {
    if i <= j {
        t.add_triplet(offset + i, offset + j, v);
    }
}

/// The elimination order of the augmented system: groups of unknowns ordered by nested
/// dissection or minimum degree of their quotient graph, each group's unknowns together.
///
/// A group is a field element (a face for face-frame fields: its `x` then its `y`) or a node of
/// an auxiliary space (its `p`, then its `s`: the order [`assemble`] relies on). The `λ` of the
/// dense rows couple to every field unknown and come last.
fn elimination_order(
    upper: &SparseColMat<usize, f64>,
    layout: &Layout,
    blocks: &GalerkinBlocks,
    ordering: FillOrdering,
) -> Result<Vec<usize>, DesignError> {
    let (field_group, field_groups) = &blocks.field_groups;
    let nodal: usize = layout.aux.iter().map(|&(_, m)| m).sum();
    let count = field_groups + nodal;
    let mut group = vec![0; layout.dense];
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (i, &g) in field_group.iter().enumerate() {
        group[i] = g;
        members[g].push(i);
    }
    if layout.biharmonic {
        for (i, &g) in field_group.iter().enumerate() {
            group[layout.fields + i] = g;
            members[g].push(layout.fields + i);
        }
    }
    let mut next = *field_groups;
    for &(p, m) in &layout.aux {
        for i in 0..m {
            group[p + i] = next;
            group[p + m + i] = next;
            members[next] = vec![p + i, p + m + i];
            next += 1;
        }
    }
    let leading = leading_pattern(upper.symbolic(), layout.dense);
    let order = match ordering {
        FillOrdering::NestedDissection => nested_dissection_of_groups(leading, &group, count)?,
        FillOrdering::Amd => minimum_degree_of_groups(leading, &group, count)?,
    };
    Ok(order
        .into_iter()
        .flat_map(|g| members[g].iter().copied())
        .chain(layout.dense..layout.total)
        .collect())
}

/// The leading `n × n` block of an upper-triangular pattern (its first `n` columns).
fn leading_pattern(
    pattern: SymbolicSparseColMatRef<'_, usize>,
    n: usize,
) -> SymbolicSparseColMatRef<'_, usize> {
    let col_ptr = &pattern.col_ptr()[..=n];
    SymbolicSparseColMatRef::new_checked(n, n, col_ptr, None, &pattern.row_idx()[..col_ptr[n]])
}

/// Approximate minimum degree (faer's) of the quotient graph of `pattern` under `group`: the
/// order of the groups.
fn minimum_degree_of_groups(
    pattern: SymbolicSparseColMatRef<'_, usize>,
    group: &[usize],
    count: usize,
) -> Result<Vec<usize>, DesignError> {
    let graph = AdjacencyGraph::quotient_of_pattern(pattern, group, count);
    let mut col_ptr = vec![0];
    let mut row_idx = Vec::new();
    for g in 0..count {
        row_idx.extend(graph.neighbours_of(g).iter().filter(|&&h| h < g));
        col_ptr.push(row_idx.len());
    }
    let nnz = row_idx.len();
    let upper = SymbolicSparseColMat::new_checked(count, count, col_ptr, None, row_idx);
    let mut forward = vec![0usize; count];
    let mut inverse = vec![0usize; count];
    let mut buffer = MemBuffer::try_new(amd::order_scratch::<usize>(count, nnz))
        .map_err(|_| SolverError::Factorization("out of memory".into()))?;
    amd::order(
        &mut forward,
        &mut inverse,
        upper.as_ref(),
        amd::Control::default(),
        MemStack::new(&mut buffer),
    )
    .map_err(|e| SolverError::Factorization(format!("minimum-degree ordering: {e:?}")))?;
    Ok(forward)
}

/// The pivots must be positive on `x, p` and negative on `y, s, λ` (see [`assemble`]);
/// otherwise the field block `T + α S_d` was not positive definite.
fn check_inertia(factor: &SparseLdlt, layout: &Layout) -> Result<(), DesignError> {
    let inertia = factor.inertia();
    let (positive, negative) = layout.inertia();
    if inertia.positive == positive && inertia.negative == negative {
        Ok(())
    } else {
        Err(DesignError::Solver(SolverError::Factorization(format!(
            "the augmented system is not of the expected inertia ({} positive, {} negative, {} \
             zero pivots; expected {positive} positive, {negative} negative): the energy is \
             not positive definite; use a positive regularization",
            inertia.positive, inertia.negative, inertia.zero
        ))))
    }
}

/// A zero pivot means the field block was singular: the same advice as a wrong inertia.
fn not_definite(error: SolverError) -> DesignError {
    match error {
        SolverError::Singular { pivot } => {
            DesignError::Solver(SolverError::Factorization(format!(
                "the augmented system has a zero pivot (unknown {pivot}): the energy is not \
                 positive definite; use a positive regularization"
            )))
        }
        other => DesignError::Solver(other),
    }
}
